"""What a user asks for, built on the problems and the runner: task-driven design
(:mod:`~mechopt.workflows.design`), the reproduction of the papers
(:mod:`~mechopt.workflows.reproduce`) and its HTML report."""

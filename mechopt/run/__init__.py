"""Running things: the seeded pymoo runner and weighted sweeps, parallel execution (the
one place for joblib and Dask), every file output (:mod:`~mechopt.run.io`), checkpoints,
run budgets, progress, the five-bar atlas and the plotting style."""

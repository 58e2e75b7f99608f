"""Analyses of any mechanism through its protocol: workspace (MIC, GCW, usable region),
global and regional performance indices, and :func:`~mechopt.analysis.evaluate.evaluate`,
the one entry point that evaluates a design of any mechanism."""

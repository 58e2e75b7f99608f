"""The lowest layer: what every mechanism and analysis shares and nothing else needs.

The mechanism protocol (:mod:`~mechopt.core.protocol`), the indices of Jacobians
(:mod:`~mechopt.core.indices`), the quadrature rules (:mod:`~mechopt.core.quadrature`),
planar geometry, one-dimensional numerics, every input limit and tolerance
(:mod:`~mechopt.core.validation`), the condition grammar, the published-record API
(:mod:`~mechopt.core.published`) and the motion profile. No module here imports a
higher layer (``tests/test_layers.py``).
"""

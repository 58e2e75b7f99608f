"""The symmetric five-bar 5R (Liu 2006, Le 2013): the model (:mod:`.model`), its LCI
over point sets (:mod:`.lci`) and its batch kernels for MIC, disk means and atlases
(:mod:`.kernels`, numba with NumPy twins)."""
from mechopt.mechanisms.five_bar.model import MODES, FiveBar

__all__ = ["FiveBar", "MODES"]

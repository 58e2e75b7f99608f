"""mechopt: dimensional synthesis of 2-DOF planar parallel manipulators."""
from .mechanisms.five_bar import FiveBar

__version__ = "0.1.0"
__all__ = ["FiveBar", "__version__"]

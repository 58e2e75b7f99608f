"""mechopt: dimensional synthesis of 2-DOF planar parallel manipulators."""
from .mechanisms.five_bar import FiveBar

__version__ = "0.1.0"
__all__ = ["FiveBar", "__version__"]

# Stan 2008 Bipod (RPRPR) and Biglide (PRRRP)
from .mechanisms.biglide import Biglide  # noqa: E402
from .mechanisms.bipod import Bipod  # noqa: E402

__all__ += ["Bipod", "Biglide"]

"""mechopt: dimensional synthesis of 2-DOF planar parallel manipulators."""
from .mechanisms.five_bar import FiveBar

__version__ = "0.1.0"
__all__ = ["FiveBar", "__version__"]

# Wu 2008 gantry and its dynamics
from .mechanisms.gantry import Gantry, dimensional_synthesis  # noqa: E402
from .dynamics import GantryDynamics, GantryInertia  # noqa: E402

__all__ += ["Gantry", "dimensional_synthesis", "GantryDynamics", "GantryInertia"]

# Stan 2008 Bipod (RPRPR) and Biglide (PRRRP)
from .mechanisms.biglide import Biglide  # noqa: E402
from .mechanisms.bipod import Bipod  # noqa: E402

__all__ += ["Bipod", "Biglide"]

"""tce: Total Complementary Energy analysis of masonry as rigid blocks in unilateral, frictional contact."""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("tce")
except PackageNotFoundError:  # running from a source tree that is not installed
    __version__ = "0.0.0+unknown"

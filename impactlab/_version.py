"""The package version, read from the installed metadata (one source: pyproject.toml)."""

from importlib import metadata

try:
    __version__ = metadata.version("impactlab")
except metadata.PackageNotFoundError:  # running from a source tree that is not installed
    __version__ = "0+unknown"

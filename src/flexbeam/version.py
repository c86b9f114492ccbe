"""flexbeam's version (one place: the package, the provenance of every result and the sweeps read it)."""

__version__ = "0.1.0"

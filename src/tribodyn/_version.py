"""The package version, in one place (read by the build, the CLI and the results' attributes)."""

__version__ = "0.2.0"

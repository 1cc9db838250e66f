"""rolling-hierarchy: the command line (app.cli) and the web explorer (app.main)."""

__version__ = "0.1.0"

"""Shared test settings."""

import warnings

warnings.filterwarnings("ignore", category=DeprecationWarning)

"""val3check: an offline checker and simulator for Stäubli VAL 3 applications."""

__version__ = "0.2.0"

"""Motion control of VAL 3 chapter 10 in simulated time (see docs/motion.md)."""

"""Contact stiffness (thesis ch. 2): fits, error analysis (sec. 2.5) and summary tables."""

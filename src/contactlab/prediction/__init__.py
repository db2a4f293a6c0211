"""Contact stiffness predicted from the scans of each tested pair (rough-contact BEM, ch. 2)."""

"""Figures: every figure-drawing function, and the paper report."""

"""Analysis of the dissertation's models: pure functions for figures, guesses and checks.

`load_factor`: chapter 6 (control set, extremal locus, hodograph, polars, arc classes).
"""

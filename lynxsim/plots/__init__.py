"""Matplotlib figures (PNG) of lynxsim's results; the Agg backend, no display."""

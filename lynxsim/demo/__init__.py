"""The main job (``lynxsim demo``): every task simulated, plotted and filmed."""

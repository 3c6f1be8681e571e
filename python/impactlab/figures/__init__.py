"""The drawing functions of impactlab's figures: the plot scripts the CLI's
--plot runs (scripts/plot_*.py), put into this package when it is built, so
that a result's plot() and the CLI draw the same figure with the same code.

Each script's draw_* function takes tables as columns by name and the run's
record, and returns a matplotlib Figure; matplotlib is imported only when a
figure is drawn.
"""

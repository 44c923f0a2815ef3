"""Everything about reproducing the university report.

* :mod:`~lynxsim.reproduce.arm_tables`: the arm numbers the report prints (its
  Figures 4 and 7 and Table 4), with SPEC's errata applied;
* :mod:`~lynxsim.reproduce.rrr_formulas`: the report's wrong 3-RRR formulas, kept
  only to show where its Figure 20 verdicts come from;
* :mod:`~lynxsim.reproduce.figure20`: the Figure 20 poses judged by simulation.
"""

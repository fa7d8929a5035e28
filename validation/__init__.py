"""The validation of exudyn-worm against the paper *Stability Analysis and Simulation of the Vibration Behavior of
Worm Gears in Drive Systems*: reference data, check groups, report.

Not part of the installed package: it lives beside its data in the source checkout and runs from the
repository root as ``python -m validation`` (see ``validation/README.md``). From Python::

    from validation import RunValidation
    summary = RunValidation(quick=True)     # nothing is written unless reportPath is given
    print(summary.lines[0])
"""
from .runner import (CHECK_GROUPS, COMMITTED_REPORT, VALIDATION_DIR, Check, CheckGroup, HalfUnit, LoadReference,
                     RegisterCheckGroup, RunValidation, ValidationContext, ValidationSummary)

__all__ = ['CHECK_GROUPS', 'COMMITTED_REPORT', 'VALIDATION_DIR', 'Check', 'CheckGroup', 'HalfUnit', 'LoadReference',
           'RegisterCheckGroup', 'RunValidation', 'ValidationContext', 'ValidationSummary']

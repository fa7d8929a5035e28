"""The AGMA 6034 friction curve against the values its source prints: the ``friction`` group of the validation.

Rows in ``validation/agma/reference.csv``; reading rule ``printed`` (half a unit of the last printed digit), fixed
with the rows before our values were computed. The source gives a formula, not a table: the values it prints at
the speeds it names are mu at rest (0.15), the factor of the low branch (0.124, mu just above rest), the switch
speed (0.0508 m/s) and the exponent factors of its metric form (2.233 and 1.185 with V in m/s). Our curve is the
ft/min form of :class:`exudyn_worm.model.friction.AgmaFriction`; the factors are recovered from our mu(v), so the rows
check the unit conversion too.
"""
from __future__ import annotations

import math
from typing import List

from exudyn_worm.model.friction import FT_PER_MIN, AgmaFriction

from .runner import Check, ValidationContext

__all__ = ['FrictionChecks']


def FrictionChecks(ctx: ValidationContext) -> List[Check]:
    """Group ``friction``: the AGMA 6034 values at the speeds the source gives.

    Parameters
    ----------
    ctx : ValidationContext
        The run's context.

    Returns
    -------
    list of Check
    """
    law = AgmaFriction()
    low, high = 0.02, 1.                     # m/s: inside the low and the high branch
    checks = [
        ctx.Compare('agma_rest', float(law.Mu(0.)), uses=()),
        ctx.Compare('agma_low_limit', float(law.Mu(1e-9)), uses=()),
        ctx.Compare('agma_switch_speed', law.SWITCH * FT_PER_MIN, uses=()),
        ctx.Compare('agma_low_factor_si', -math.log(float(law.Mu(low)) / law.LOW[0]) / low ** law.LOW[2], uses=()),
        ctx.Compare('agma_high_factor_si', -math.log((float(law.Mu(high)) - law.HIGH[3]) / law.HIGH[0])
                    / high ** law.HIGH[2], uses=()),
    ]
    return checks

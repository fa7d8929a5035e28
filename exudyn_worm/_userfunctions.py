"""Recording of Exudyn user functions from backend-neutral Python laws.

A law is written once as ``law(t, q, q_t, ops)`` (generalized forces) or ``law(t, ops)`` (constraint
offset) with the arithmetic backend ``ops``; here it becomes either an Exudyn symbolic user function
(evaluated in C++) or a plain Python user function.
"""
from __future__ import annotations

from typing import Any, Callable, Sequence, Tuple

import numpy as np

from .contact import MATH_OPS, SymbolicOps

__all__ = ['AddGenericForce', 'SetOffsetFunction']

_KEEP_ALIVE = 'exudynWorm.symbolicUserFunctions'   # mbs.variables key: expression trees must outlive the solve


def _Record(mbs, fnDict, userFunctionName, itemIndex):
    import exudyn as exu
    uf = exu.symbolic.UserFunction()
    uf.SetUserFunctionFromDict(mbs, fnDict, userFunctionName, itemIndex, 'None')
    mbs.variables.setdefault(_KEEP_ALIVE, []).append((uf, fnDict))
    return uf


def AddGenericForce(mbs, nodeNumbers: Sequence[Any], law: Callable, name: str = '',
                    useSymbolic: bool = True) -> Tuple[Any, Any]:
    """Add an ``ObjectGenericODE2`` on one-coordinate nodes whose forces are ``law(t, q, q_t, ops)``.

    Returns ``(objectNumber, userFunction)``.
    """
    import exudyn as exu
    from exudyn.itemInterface import ObjectGenericODE2
    n = len(nodeNumbers)
    zeros = np.zeros((n, n))
    oItem = mbs.AddObject(ObjectGenericODE2(nodeNumbers=list(nodeNumbers), massMatrix=zeros,
                                            stiffnessMatrix=zeros, dampingMatrix=zeros, name=name))
    if useSymbolic:
        esym = exu.symbolic
        ops = SymbolicOps()
        recording = esym.GetRecording()
        esym.SetRecording(True)
        try:
            args = [mbs, esym.Real('t', 0.), esym.Real('itemNumber', 0), esym.Vector('q', [0.] * n),
                    esym.Vector('q_t', [0.] * n)]
            forces = law(args[1], args[3], args[4], ops)
            fnDict = {'functionName': 'GenericForce', 'argList': args,
                      'argTypeList': ['MainSystem', 'Real', 'Index', 'StdVector', 'StdVector'],
                      'returnValue': esym.Vector(list(forces)), 'returnType': 'StdVector'}
            userFunction = _Record(mbs, fnDict, 'forceUserFunction', oItem)
        finally:
            esym.SetRecording(recording)
    else:
        def userFunction(mbs, t, itemNumber, q, q_t):
            return list(law(t, q, q_t, MATH_OPS))
    mbs.SetObjectParameter(oItem, 'forceUserFunction', userFunction)
    return oItem, userFunction


def SetOffsetFunction(mbs, objectNumber, law: Callable, useSymbolic: bool = True):
    """Set ``offsetUserFunction`` (and ``offsetUserFunction_t`` for index-2 solvers) of a
    coordinate constraint from ``law(t, ops) -> (offset, offsetRate)``."""
    import exudyn as exu
    if useSymbolic:
        esym = exu.symbolic
        ops = SymbolicOps()
        recording = esym.GetRecording()
        esym.SetRecording(True)
        try:
            ufs = []
            for k, ufName in enumerate(('offsetUserFunction', 'offsetUserFunction_t')):
                args = [mbs, esym.Real('t', 0.), esym.Real('itemNumber', 0), esym.Real('lOffset', 0.)]
                value = law(args[1], ops)[k]
                fnDict = {'functionName': 'Offset', 'argList': args,
                          'argTypeList': ['MainSystem', 'Real', 'Index', 'Real'],
                          'returnValue': value, 'returnType': 'Real'}
                ufs.append(_Record(mbs, fnDict, ufName, objectNumber))
        finally:
            esym.SetRecording(recording)
    else:
        ufs = [lambda mbs, t, itemNumber, lOffset: law(t, MATH_OPS)[0],
               lambda mbs, t, itemNumber, lOffset: law(t, MATH_OPS)[1]]
    mbs.SetObjectParameter(objectNumber, 'offsetUserFunction', ufs[0])
    mbs.SetObjectParameter(objectNumber, 'offsetUserFunction_t', ufs[1])
    return ufs

"""Recording of Exudyn user functions from backend-neutral Python laws.

A law is written once as ``law(t, q, q_t, ops)`` (generalized forces) or ``law(t, ops)`` (constraint
offset) with the arithmetic backend ``ops``; here it becomes either an Exudyn symbolic user function
(evaluated in C++) or a plain Python user function.
"""
from __future__ import annotations

from typing import Any, Callable, Sequence, Tuple

import numpy as np

from .contact import MATH_OPS, SymbolicOps

__all__ = ['AddGenericForce', 'SetGenericForceLaw', 'SetOffsetFunction']

_KEEP_ALIVE = 'exudynWorm.symbolicUserFunctions'   # mbs.variables key: expression trees must outlive the solve


def _RecordSymbolic(mbs, itemIndex, userFunctionName: str, arguments, returnType: str, build: Callable):
    """Record ``build(args, ops)`` as an Exudyn symbolic user function of ``itemIndex``.

    ``arguments`` lists ``(name, type, size)`` after the leading MainSystem, with Exudyn's type names
    (``'Real'``, ``'Index'``, ``'StdVector'``); the returned expression has type ``returnType``.
    """
    import exudyn as exu
    esym = exu.symbolic
    recording = esym.GetRecording()
    esym.SetRecording(True)
    try:
        args = [mbs] + [esym.Vector(name, [0.] * size) if typ == 'StdVector' else esym.Real(name, 0.)
                        for name, typ, size in arguments]
        value = build(args, SymbolicOps())
        fnDict = {'functionName': userFunctionName, 'argList': args,
                  'argTypeList': ['MainSystem'] + [typ for _, typ, _ in arguments],
                  'returnValue': esym.Vector(list(value)) if returnType == 'StdVector' else value,
                  'returnType': returnType}
        uf = esym.UserFunction()
        uf.SetUserFunctionFromDict(mbs, fnDict, userFunctionName, itemIndex, 'None')
    finally:
        esym.SetRecording(recording)
    mbs.variables.setdefault(_KEEP_ALIVE, []).append((uf, fnDict))
    return uf


def AddGenericForce(mbs, nodeNumbers: Sequence[Any], law: Callable, name: str = '',
                    useSymbolic: bool = True) -> Tuple[Any, Any]:
    """Add an ``ObjectGenericODE2`` on one-coordinate nodes whose forces are ``law(t, q, q_t, ops)``.

    Returns ``(objectNumber, userFunction)``.
    """
    from exudyn.itemInterface import ObjectGenericODE2
    n = len(nodeNumbers)
    zeros = np.zeros((n, n))
    oItem = mbs.AddObject(ObjectGenericODE2(nodeNumbers=list(nodeNumbers), massMatrix=zeros,
                                            stiffnessMatrix=zeros, dampingMatrix=zeros, name=name))
    return oItem, SetGenericForceLaw(mbs, oItem, n, law, useSymbolic)


def SetGenericForceLaw(mbs, objectNumber, n: int, law: Callable, useSymbolic: bool = True):
    """(Re)set the ``forceUserFunction`` of an ``ObjectGenericODE2`` on ``n`` one-coordinate nodes to
    ``law(t, q, q_t, ops)``; returns the user function."""
    oItem = objectNumber
    if useSymbolic:
        userFunction = _RecordSymbolic(mbs, oItem, 'forceUserFunction',
                                       [('t', 'Real', 1), ('itemNumber', 'Index', 1), ('q', 'StdVector', n),
                                        ('q_t', 'StdVector', n)], 'StdVector',
                                       lambda args, ops: law(args[1], args[3], args[4], ops))
    else:
        def userFunction(mbs, t, itemNumber, q, q_t):
            return list(law(t, q, q_t, MATH_OPS))
    mbs.SetObjectParameter(oItem, 'forceUserFunction', userFunction)
    return userFunction


def SetOffsetFunction(mbs, objectNumber, law: Callable, useSymbolic: bool = True):
    """Set ``offsetUserFunction`` (and ``offsetUserFunction_t`` for index-2 solvers) of a
    coordinate constraint from ``law(t, ops) -> (offset, offsetRate)``."""
    if useSymbolic:
        ufs = [_RecordSymbolic(mbs, objectNumber, ufName,
                               [('t', 'Real', 1), ('itemNumber', 'Index', 1), ('lOffset', 'Real', 1)], 'Real',
                               lambda args, ops, k=k: law(args[1], ops)[k])
               for k, ufName in enumerate(('offsetUserFunction', 'offsetUserFunction_t'))]
    else:
        ufs = [lambda mbs, t, itemNumber, lOffset: law(t, MATH_OPS)[0],
               lambda mbs, t, itemNumber, lOffset: law(t, MATH_OPS)[1]]
    mbs.SetObjectParameter(objectNumber, 'offsetUserFunction', ufs[0])
    mbs.SetObjectParameter(objectNumber, 'offsetUserFunction_t', ufs[1])
    return ufs

"""Recording of Exudyn user functions from backend-neutral Python laws.

A law is written once as ``law(t, q, q_t, ops)`` (generalized forces) or ``law(t, ops)`` (constraint
offset) with the arithmetic backend ``ops``; here it becomes either an Exudyn symbolic user function
(evaluated in C++) or a plain Python user function.
"""
from __future__ import annotations

from numbers import Real
from typing import Any, Callable, Sequence, Tuple

import numpy as np

from ..model.contact import SymbolicOps
from ..model.friction import MATH_OPS

__all__ = ['AddGenericForce', 'AddCoordinateForce',
           'SetGenericForceLaw', 'SetOffsetFunction', 'CheckSymbolicLaw', 'CheckForceLaw',
           'CheckOffsetLaw', 'CheckPlainForceLaw', 'CheckPlainOffsetLaw']

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
        # the MainSystem argument is a placeholder that the recording never reads: None instead of mbs, because
        # the user function keeps fnDict, the system keeps the user function, and mbs in fnDict would close a
        # cycle through C++ objects that Python's garbage collector cannot see (the system would never be freed)
        args = [None] + [esym.Vector(name, [0.] * size) if typ == 'StdVector' else esym.Real(name, 0.)
                         for name, typ, size in arguments]
        value = build(args, SymbolicOps())
        fnDict = {'functionName': userFunctionName, 'argList': args,
                  'argTypeList': ['MainSystem'] + [typ for _, typ, _ in arguments],
                  'returnValue': (value if isinstance(value, esym.Vector) else esym.Vector(list(value)))
                  if returnType == 'StdVector' else value if isinstance(value, esym.Real) else esym.Real(float(value)),
                  'returnType': returnType}
        uf = esym.UserFunction()
        uf.SetUserFunctionFromDict(mbs, fnDict, userFunctionName, itemIndex, 'None')
    finally:
        esym.SetRecording(recording)
    mbs.variables.setdefault(_KEEP_ALIVE, []).append((uf, fnDict))
    return uf


#: sample states (t in s, coordinate, speed) at which a recorded law is compared with plain Python: away from
#: 0 (the value the arguments have while recording), both signs, several magnitudes
_SAMPLES = ((0.137, -2.1, 0.61), (1.73, 0.35, -31.3), (11.3, 7.9, 52.7), (97.1, -130.3, -0.043))
_FORCE_ARGUMENTS = lambda n: [('t', 'Real', 1), ('itemNumber', 'Index', 1), ('q', 'StdVector', n),
                              ('q_t', 'StdVector', n)]
_OFFSET_ARGUMENTS = [('t', 'Real', 1), ('itemNumber', 'Index', 1), ('lOffset', 'Real', 1)]
#: ``springForceUserFunction`` of ``ObjectConnectorCoordinateSpringDamper``: the coordinate (without its reference
#: value) and its velocity are ``deltaL``, ``deltaL_t`` for a spring-damper from ground
_SPRING_ARGUMENTS = [('t', 'Real', 1), ('itemNumber', 'Index', 1), ('deltaL', 'Real', 1), ('deltaL_t', 'Real', 1),
                     ('stiffness', 'Real', 1), ('damping', 'Real', 1), ('offset', 'Real', 1)]
#: arguments that are constants of the item, not the state: left out of a message's sample state
_CONSTANT_ARGUMENTS = {'lOffset', 'stiffness', 'damping', 'offset'}


def _Flat(value):
    if hasattr(value, 'NumberOfItems'):        # a symbolic vector (e.g. a matrix-vector product)
        return [float(x) for x in value.Evaluate()]
    items = list(value) if isinstance(value, (list, tuple)) else [value]
    return [float(x.Evaluate()) if hasattr(x, 'Evaluate') else float(x) for x in items]


def _PlainArguments(arguments, t, x, v) -> list:
    """Plain-Python arguments of a law at sample state (t, x, v): ``[None, ...]`` in the order of ``arguments``."""
    plain = [None]
    for name, typ, size in arguments:
        if typ == 'StdVector':
            plain.append([(x if name == 'q' else v) * (1. + 0.29 * k) for k in range(size)])
        else:
            plain.append({'t': t, 'deltaL': x, 'deltaL_t': v}.get(name, 0.))
    return plain


def _CheckPlainCall(where: str, arguments, build: Callable, signature: str, returnSize) -> None:
    """Call the law once in plain Python (``MATH_OPS``) at the first sample state: a TypeError there is the law's
    own (wrong number of arguments, ...), and what it returns must be numbers, before anything is recorded."""
    t, x, v = _SAMPLES[0]
    try:
        value = build(_PlainArguments(arguments, t, x, v), MATH_OPS)
    except TypeError as err:
        raise TypeError(f"{where}: calling the law in plain Python failed with TypeError: {err}"
                        f"{'; it must be callable as ' + signature if signature else ''}") from err
    except (ArithmeticError, ValueError):          # not defined at this state: the comparison skips it
        return
    items = list(value) if isinstance(value, (list, tuple)) else [value]
    bad = [item for item in items if isinstance(item, bool) or not isinstance(item, (Real, np.number))]
    if bad or (returnSize is not None and len(items) != returnSize):
        expected = 'a number' if returnSize in (None, 1) else f'{returnSize} numbers'
        got = f"{type(bad[0]).__name__} {bad[0]!r}" if bad else f"{len(items)} values {value!r}"
        raise TypeError(f"{where}: the law must return {expected}, got {got} when called in plain Python")


def CheckSymbolicLaw(where: str, arguments, build: Callable, signature: str = '', returnSize=None) -> None:
    """Check that ``build(args, ops)`` records as the same function in C++ as it computes in Python.

    The law is first called once in plain Python (``MATH_OPS``): a ``TypeError`` there (e.g. the wrong number of
    arguments) is reported as the law's own error, and it must return numbers. A law written with a Python
    ``if``, ``and``/``or``, the built-in ``min``/``max`` or ``math`` functions on its arguments is evaluated once
    while it is recorded (with the arguments at 0) and becomes a constant in the symbolic user function,
    without any error. This records the law, evaluates the recording at a few sample states (:data:`_SAMPLES`)
    and compares with the law evaluated in plain Python (``MATH_OPS``) there.

    Parameters
    ----------
    where : str
        The builder that received the law (named in the messages).
    arguments : list of (name, type, size)
        The user function's arguments after the MainSystem (as for ``_RecordSymbolic``).
    build : callable
        ``build(args, ops)`` with ``args[0]`` the MainSystem (None here).
    signature : str, optional
        How the user's law is called, for the message of a failed call (e.g. ``'law(phi, omega, t, ops)'``).
    returnSize : int, optional
        Number of values ``build`` must return (None: not checked).

    Raises
    ------
    ValueError
        If recording and Python differ at a sample state; the message names the likely cause.
    TypeError
        If the law fails when called in plain Python, returns something else than numbers, or cannot be
        recorded at all (e.g. a numpy function applied to a symbolic argument).
    """
    import exudyn as exu
    esym = exu.symbolic
    _CheckPlainCall(where, arguments, build, signature, returnSize)
    recording = esym.GetRecording()
    esym.SetRecording(True)
    try:
        args = [None] + [esym.Vector(name, [0.] * size) if typ == 'StdVector' else esym.Real(name, 0.)
                         for name, typ, size in arguments]
        try:
            value = build(args, SymbolicOps())
        except TypeError as err:
            raise TypeError(f"{where}: the law cannot be recorded as a symbolic (C++) user function ({err}); write "
                            f"it with the functions of 'ops' (ops.sin, ops.cos, ops.where, ops.min, ...) instead of "
                            f"math or numpy, or pass useSymbolic=False") from err
        for t, x, v in _SAMPLES:
            plain = _PlainArguments(arguments, t, x, v)
            for (name, typ, size), arg, sample in zip(arguments, args[1:], plain[1:]):
                if typ == 'StdVector':
                    arg.SetVector(sample)
                else:
                    arg.SetValue(sample)
            try:
                expected = _Flat(build(plain, MATH_OPS))
            except (ArithmeticError, ValueError):            # the law is not defined there: no comparison
                continue
            got = _Flat(value)
            if any(not np.isclose(g, e, rtol=1e-9, atol=1e-12) and not (np.isnan(g) and np.isnan(e))
                   for g, e in zip(got, expected)):
                state = ', '.join(f"{name} = {p:g}" if not isinstance(p, list) else
                                  f"{name} = [{', '.join(f'{c:g}' for c in p)}]"
                                  for (name, typ, _), p in zip(arguments, plain[1:]) if typ != 'Index'
                                  and name not in _CONSTANT_ARGUMENTS)
                raise ValueError(
                    f"{where}: the law gives {got if len(got) > 1 else got[0]} when recorded as a symbolic (C++) "
                    f"user function but {expected if len(expected) > 1 else expected[0]} in Python at {state}. "
                    f"Likely cause: a Python 'if', 'and'/'or', built-in min/max or a math function applied to the "
                    f"law's arguments: it is evaluated once while recording and gives a constant. Write the law "
                    f"with ops.where(condition, a, b), ops.min, ops.max, ops.cos, ... or pass useSymbolic=False")
    finally:
        esym.SetRecording(recording)


def CheckForceLaw(where: str, n: int, law: Callable, signature: str = 'law(t, q, q_t, ops)') -> None:
    """:func:`CheckSymbolicLaw` for a generalized-force law ``law(t, q, q_t, ops)`` on ``n`` coordinates."""
    CheckSymbolicLaw(where, _FORCE_ARGUMENTS(n), lambda args, ops: law(args[1], args[3], args[4], ops), signature, n)


def CheckPlainForceLaw(where: str, n: int, law: Callable, signature: str = 'law(t, q, q_t, ops)') -> None:
    """Call a generalized-force law once in plain Python: a ``TypeError`` or a result that is not ``n`` numbers
    is refused (the check of :func:`CheckForceLaw` without the symbolic recording)."""
    _CheckPlainCall(where, _FORCE_ARGUMENTS(n), lambda args, ops: law(args[1], args[3], args[4], ops), signature, n)


def CheckPlainOffsetLaw(where: str, law: Callable, signature: str = 'AngleAndSpeed(t, ops)') -> None:
    """Call a constraint-offset law once in plain Python: a ``TypeError`` or a result that is not two numbers
    is refused (the check of :func:`CheckOffsetLaw` without the symbolic recording)."""
    _CheckPlainCall(where, _OFFSET_ARGUMENTS, lambda args, ops: list(law(args[1], ops))[:2], signature, 2)


def CheckOffsetLaw(where: str, law: Callable, signature: str = 'AngleAndSpeed(t, ops)') -> None:
    """:func:`CheckSymbolicLaw` for a constraint-offset law ``law(t, ops) -> (offset, offsetRate)``."""
    CheckSymbolicLaw(where, _OFFSET_ARGUMENTS, lambda args, ops: list(law(args[1], ops))[:2], signature, 2)


def AddGenericForce(mbs, nodeNumbers: Sequence[Any], law: Callable, name: str = '',
                    useSymbolic: bool = True, where: str = 'AddGenericForce',
                    signature: str = 'law(t, q, q_t, ops)') -> Tuple[Any, Any]:
    """Add an ``ObjectGenericODE2`` on one-coordinate nodes whose forces are ``law(t, q, q_t, ops)``.

    With ``useSymbolic`` the law is first checked with :func:`CheckSymbolicLaw` (errors name ``where``),
    so that nothing is added for a law that would be recorded wrongly. Returns ``(objectNumber, userFunction)``.
    """
    from exudyn.itemInterface import ObjectGenericODE2
    n = len(nodeNumbers)
    if useSymbolic:
        CheckForceLaw(where, n, law, signature)
    else:
        CheckPlainForceLaw(where, n, law, signature)
    zeros = np.zeros((n, n))
    oItem = mbs.AddObject(ObjectGenericODE2(nodeNumbers=list(nodeNumbers), massMatrix=zeros,
                                            stiffnessMatrix=zeros, dampingMatrix=zeros, name=name))
    return oItem, SetGenericForceLaw(mbs, oItem, n, law, useSymbolic, check=False)


def AddCoordinateForce(mbs, nodeNumber, markerNumber, law: Callable, name: str = '', useSymbolic: bool = True,
                       where: str = 'AddCoordinateForce', signature: str = 'law(t, x, v, ops)') -> Tuple[Any, Any]:
    """Add the force ``law(t, x, v, ops)`` on the coordinate of a one-coordinate node (``x`` its value without the
    reference value, ``v`` its velocity), as an ``ObjectConnectorCoordinateSpringDamper`` from ground whose
    ``springForceUserFunction`` returns it.

    The same generalized force as a one-node ``ObjectGenericODE2`` (:func:`AddGenericForce`), at a smaller cost in
    Exudyn 1.13.6: the reel changer's load this way makes P1's whole solve 11 % fewer instructions with bit-identical
    results (benchmarks/README.md). With ``useSymbolic`` the law is first checked with :func:`CheckSymbolicLaw`
    (errors name ``where``), so that nothing is added for a law that would be recorded wrongly. Returns
    ``(objectNumber, userFunction)``.
    """
    from exudyn.itemInterface import CoordinateSpringDamper, MarkerNodeCoordinate, NodePointGround
    check = lambda args, ops: law(args[1], args[3], args[4], ops)
    if useSymbolic:
        CheckSymbolicLaw(where, _SPRING_ARGUMENTS, check, signature, 1)
    else:
        _CheckPlainCall(where, _SPRING_ARGUMENTS, check, signature, 1)
    ground = mbs.AddNode(NodePointGround(name=name + 'Ground' if name else ''))
    mGround = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=ground, coordinate=0))
    oItem = mbs.AddObject(CoordinateSpringDamper(markerNumbers=[mGround, markerNumber], stiffness=0., damping=0.,
                                                 name=name))
    # Exudyn applies the spring force F as -F to the second marker's coordinate: the user function returns -law
    if useSymbolic:
        userFunction = _RecordSymbolic(mbs, oItem, 'springForceUserFunction', _SPRING_ARGUMENTS, 'Real',
                                       lambda args, ops: -law(args[1], args[3], args[4], ops))
    else:
        def userFunction(mbs, t, itemNumber, deltaL, deltaL_t, stiffness, damping, offset):
            return -float(law(t, deltaL, deltaL_t, MATH_OPS))
    mbs.SetObjectParameter(oItem, 'springForceUserFunction', userFunction)
    return oItem, userFunction


def SetGenericForceLaw(mbs, objectNumber, n: int, law: Callable, useSymbolic: bool = True, check: bool = True,
                       where: str = 'SetGenericForceLaw'):
    """(Re)set the ``forceUserFunction`` of an ``ObjectGenericODE2`` on ``n`` one-coordinate nodes to
    ``law(t, q, q_t, ops)`` (checked with :func:`CheckSymbolicLaw` if ``check``); returns the user function."""
    oItem = objectNumber
    if useSymbolic:
        if check:
            CheckForceLaw(where, n, law)
        userFunction = _RecordSymbolic(mbs, oItem, 'forceUserFunction', _FORCE_ARGUMENTS(n), 'StdVector',
                                       lambda args, ops: law(args[1], args[3], args[4], ops))
    else:
        def userFunction(mbs, t, itemNumber, q, q_t):
            return list(law(t, q, q_t, MATH_OPS))
    mbs.SetObjectParameter(oItem, 'forceUserFunction', userFunction)
    return userFunction


def SetOffsetFunction(mbs, objectNumber, law: Callable, useSymbolic: bool = True, check: bool = True,
                      where: str = 'SetOffsetFunction'):
    """Set ``offsetUserFunction`` (and ``offsetUserFunction_t`` for index-2 solvers) of a
    coordinate constraint from ``law(t, ops) -> (offset, offsetRate)`` (checked with :func:`CheckOffsetLaw`
    if ``check``)."""
    if useSymbolic:
        if check:
            CheckOffsetLaw(where, law)
        ufs = [_RecordSymbolic(mbs, objectNumber, ufName, _OFFSET_ARGUMENTS, 'Real',
                               lambda args, ops, k=k: law(args[1], ops)[k])
               for k, ufName in enumerate(('offsetUserFunction', 'offsetUserFunction_t'))]
    else:
        ufs = [lambda mbs, t, itemNumber, lOffset: law(t, MATH_OPS)[0],
               lambda mbs, t, itemNumber, lOffset: law(t, MATH_OPS)[1]]
    mbs.SetObjectParameter(objectNumber, 'offsetUserFunction', ufs[0])
    mbs.SetObjectParameter(objectNumber, 'offsetUserFunction_t', ufs[1])
    return ufs

"""What a parameter study varies: the values of each key (``--vary`` grids and lists), the points of a full
factorial or zipped study, the :class:`Study` itself and the shards of a job array."""
from __future__ import annotations

import json
import math
import operator
from collections.abc import Sequence as _SequenceABC
from dataclasses import dataclass, field
from typing import Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from ...params.parameters import PARAMETERS
from ...drive.presets import PARAMETER_UNITS, ApplyOverrides, CheckParameterKeys, DriveSideChain, LoadSideChain
from ...items.results import CheckWindows
from ..._checks import CheckPositive
from ...drive.duty import IsReelChangerDuty
from ...drive.wholedrive import Drive
from ..simulation.reelchanger import DefaultWindows
from .studypoint import RunTask

__all__ = ['MAX_RUNS', 'MAX_VALUES', 'BYTES_PER_RUN', 'Variation', 'ParseVariation', 'StudyPoints', 'StudyGrid', 'Study',
           'ParseShard', 'ShardIndices', 'ShardSize', 'CheckStudySize']


_NUMBER_OF_DEFAULT_WINDOWS = 3          # DefaultWindows: lift, lower, lift

#: runs one call of :func:`~exudyn_worm.analysis.studies.study.RunStudy` (a study, or one shard of it) may hold: the parent
#: keeps each run's work item and row until the call ends (about 9 kB per run, :data:`BYTES_PER_RUN`), so the
#: limit keeps it below 1 GB; a larger study runs as shards (``shard='i/N'``, ``exudyn-worm sweep --shard i/N``)
MAX_RUNS = 100_000
#: memory of the parent per run of a study, in bytes: work item, its pickle, future and result row (measured with
#: tracemalloc over 2,000 runs of a P1 study with 47 columns: 8.7 kB)
BYTES_PER_RUN = 9_000
#: values one variation may hold (each is kept in the study's definition and its JSON sidecar)
MAX_VALUES = 1_000_000


@dataclass(frozen=True)
class Variation:
    """The values one parameter takes in a study.

    Attributes
    ----------
    key : str
        Parameter name (a key of :data:`~exudyn_worm.drive.presets.PARAMETER_UNITS`).
    values : tuple of float
        Values in SI units, in study order.
    text : str
        The specification as given (for the record).
    """
    key: str
    values: Tuple[float, ...]
    text: str = ''

    def ToDict(self) -> Dict:
        """JSON-ready ``{'key', 'unit', 'values', 'text'}``."""
        return {'key': self.key, 'unit': PARAMETER_UNITS[self.key], 'values': list(self.values), 'text': self.text}


def ParseVariation(text: str, log: bool = False) -> Variation:
    """Parse one ``--vary`` specification.

    Parameters
    ----------
    text : str
        ``KEY=START:STOP:COUNT`` for a grid of COUNT values from START to STOP (both included; optional
        fourth field ``lin`` or ``log``), or ``KEY=V1,V2,...`` for a list. Every value is a plain SI number
        or has units, as ``--set`` accepts (:func:`~exudyn_worm.drive.config.ParseQuantity`), e.g.
        ``'J1=0.01:0.4:8'``, ``'kT=700:14000:12:log'``, ``'backlash=0,0.25mm,0.5 mm'``,
        ``'backlash=0:1mm:9'``.
    log : bool, optional
        Space a grid logarithmically (default linear; a fourth field ``lin``/``log`` wins).

    Returns
    -------
    Variation

    Raises
    ------
    ValueError
        For a malformed specification, an unknown key, a bad value or unit, COUNT < 1, a grid with
        COUNT > 1 and START = STOP, or a log grid with START or STOP <= 0.
    """
    where = 'ParseVariation'
    if not isinstance(text, str):
        raise TypeError(f"{where}: expected a string 'KEY=START:STOP:COUNT' or 'KEY=V1,V2,...', "
                        f"got {type(text).__name__} {text!r}")
    key, sep, spec = text.partition('=')
    key, spec = key.strip(), spec.strip()
    if not sep or not key or not spec:
        raise ValueError(f"{where}: expected KEY=START:STOP:COUNT or KEY=V1,V2,... "
                         f"(e.g. 'J1=0.01:0.4:8' or 'backlash=0,0.25mm,0.5mm'), got {text!r}")
    if key not in PARAMETERS:
        raise ValueError(PARAMETERS.UnknownKeyMessage(f"{where}: {text!r}", key))
    if PARAMETERS[key].kind != 'number':
        raise ValueError(f"{where}: {text!r}: a study sweeps numbers; {key!r} takes a {PARAMETERS[key].kind} "
                         f"({PARAMETERS[key].rangeText}): set it with --set or in the base set instead")
    context = f"{where}: {text!r}"
    if ':' in spec:
        fields = [f.strip() for f in spec.split(':')]
        if len(fields) == 4 and fields[3].lower() in ('lin', 'log'):
            log = fields[3].lower() == 'log'
            fields = fields[:3]
        if len(fields) != 3:
            raise ValueError(f"{context}: a grid is START:STOP:COUNT[:lin|log], e.g. 'J1=0.01:0.4:8'")
        start, stop = (PARAMETERS.Parse(key, f, f"{context}: {name}") if f
                       else _Raise(context, 'START and STOP must be given') for f, name in zip(fields[:2], ('START', 'STOP')))
        try:
            count = int(fields[2])
        except ValueError:
            raise ValueError(f"{context}: COUNT must be a whole number >= 1, got {fields[2]!r}") from None
        if count < 1:
            raise ValueError(f"{context}: COUNT must be >= 1, got {count}")
        _CheckValueCount(context, count)
        if count > 1 and start == stop:
            raise ValueError(f"{context}: START and STOP must differ for COUNT > 1")
        if log:
            if start <= 0 or stop <= 0:
                raise ValueError(f"{context}: a log grid needs START and STOP > 0 "
                                 f"(in {PARAMETER_UNITS[key] or 'SI'}), got {start:g} and {stop:g}")
            values = np.geomspace(start, stop, count) if count > 1 else np.array([start])
        else:
            values = np.linspace(start, stop, count)
        values = [float(v) for v in values]
        values[0] = start                                  # exact ends, no rounding from exp/log
        values[-1] = stop if count > 1 else start
    else:
        items = [item.strip() for item in spec.split(',')]
        _CheckValueCount(context, len(items))
        if any(not item for item in items):
            raise ValueError(f"{context}: empty value in the list (V1,V2,...)")
        values = [PARAMETERS.Parse(key, item, context) for item in items]
    for value in values:                  # the range of the key (J1 > 0, z1 a whole number), before any run
        PARAMETERS.Check(key, value, context)
    return Variation(key, tuple(values), text)


def _CheckValueCount(context: str, count: int) -> None:
    if count > MAX_VALUES:        # refused before the values are built
        raise ValueError(f"{context}: {count:,} values are above the limit of {MAX_VALUES:,} values of one varied "
                         f"parameter; give fewer (a study of more runs varies several parameters and runs as "
                         f"shards, --shard i/N)")


def _Raise(context, message):
    raise ValueError(f"{context}: {message}")


def StudyPoints(variations: Sequence[Variation], zipped: bool = False) -> List[Dict[str, float]]:
    """The points of a study: the full factorial of the variations (the first varies slowest), or zipped.

    Parameters
    ----------
    variations : sequence of Variation
        One per varied key; keys must be distinct.
    zipped : bool, optional
        Pair the i-th values of all variations (they must have equal lengths) instead of the full factorial.

    Returns
    -------
    list of dict
        One ``{key: value}`` per point; ``[{}]`` for no variation (one run of the base set).

    Raises
    ------
    ValueError
        For a key varied twice, or zipped variations of different lengths.
    """
    return list(StudyGrid(variations, zipped, 'StudyPoints'))


class StudyGrid(_SequenceABC):
    """The points of a study as a sequence that builds each point when asked (the order of :func:`StudyPoints`):
    its size is known at once, and no memory is taken by the points of a grid however large.

    Parameters
    ----------
    variations : sequence of Variation
        One per varied key; keys must be distinct.
    zipped : bool, optional
        Pair the i-th values of all variations (equal lengths) instead of the full factorial.
    where : str, optional
        Prefix of the error messages.

    Raises
    ------
    ValueError
        For a key varied twice, or zipped variations of different lengths.
    """

    def __init__(self, variations: Sequence[Variation], zipped: bool = False, where: str = 'StudyGrid'):
        keys = [v.key for v in variations]
        repeated = sorted({k for k in keys if keys.count(k) > 1})
        if repeated:
            raise ValueError(f"{where}: parameter(s) {', '.join(repeated)} varied more than once")
        if zipped and len({len(v.values) for v in variations}) > 1:
            lengths = ', '.join(f"{v.key}: {len(v.values)}" for v in variations)
            raise ValueError(f"{where}: zipped variations need equal numbers of values, got {lengths}")
        self._keys, self._values, self._zipped = keys, [tuple(v.values) for v in variations], bool(zipped)
        self._size = (len(self._values[0]) if self._values else 1) if zipped else math.prod(map(len, self._values))

    def __len__(self) -> int:
        return self._size

    def __getitem__(self, index):
        if isinstance(index, slice):
            return [self[i] for i in range(*index.indices(self._size))]
        i = operator.index(index)
        if i < 0:
            i += self._size
        if not 0 <= i < self._size:
            raise IndexError(f"StudyGrid: point {index} of a study of {self._size} points")
        if self._zipped:
            return {k: values[i] for k, values in zip(self._keys, self._values)}
        point = {}
        for k, values in zip(reversed(self._keys), reversed(self._values)):   # the first key varies slowest
            i, j = divmod(i, len(values))
            point[k] = values[j]
        return {k: point[k] for k in self._keys}

    def __eq__(self, other) -> bool:
        if isinstance(other, StudyGrid):         # two grids: by their definition, without building a point
            return (self._keys, self._values, self._size) == (other._keys, other._values, other._size) and (
                self._zipped == other._zipped or len(self._keys) < 2)
        return isinstance(other, _SequenceABC) and len(other) == len(self) and all(a == b for a, b in zip(self, other))

    __hash__ = None

    def Shape(self) -> str:
        """``'J1: 10000 x kT: 10000'`` (zipped: ``'J1, kT zipped: 100'``), for messages."""
        if self._zipped:
            return f"{', '.join(self._keys)} zipped: {self._size:,}"
        return ' x '.join(f"{k}: {len(v):,}" for k, v in zip(self._keys, self._values)) or 'no variation'


@dataclass
class Study:
    """A parameter study of the reel changer.

    Parameters
    ----------
    base : mapping
        The flat parameter set every point starts from (e.g. :func:`~exudyn_worm.drive.config.ResolveParameters`).
    variations : sequence of Variation
        The varied parameters (:func:`ParseVariation`).
    zipped : bool, optional
        Pair the variations instead of the full factorial.
    windows : sequence of (float, float), optional
        Evaluation windows in s (default: the lift / lower / lift phases of each point's first rotation,
        :func:`~exudyn_worm.analysis.simulation.reelchanger.DefaultWindows`, clipped to ``endTime`` when that is shorter; the
        columns of a window that does not exist stay empty). For a duty other than the reel changer's
        (:mod:`exudyn_worm.drive.duty`) the default is the phases of the first point's duty up to ``endTime`` (or its
        :func:`~exudyn_worm.analysis.simulation.reelchanger.DefaultSimulatedTime`), the same windows for every run (the columns of a
        study are fixed); a window counts as lowering if its middle lies in a lowering phase of the run's duty.
    endTime : float, optional
        Simulated time in s (default: one rotation of each point, at least up to the last window).
    stepSize : float, optional
        Time step in s (default, per run: the drive's :func:`~exudyn_worm.analysis.simulation.stepsize.RecommendedStepSize`, the
        step ``simulate`` and ``check --simulate`` use, so a run and ``simulate`` of the same drive agree).
    source : str, optional
        Where the base set came from (for the record).
    maxSteps : int, optional
        Refuse (record as failed) runs of more solver steps than this (default, None:
        :data:`~exudyn_worm.analysis.simulation.reelchanger.MAX_STEPS`, as ``simulate``).
    checkStep : bool, optional
        Run each point again at half the step and record a window whose chatter verdict changes as
        ``'unresolved'`` (True), never (False), or (None, default) where the point's linear margin is small
        (:func:`~exudyn_worm.analysis.simulation.stepsize.StepCheckByDefault`), as ``simulate``.
    """
    base: Mapping[str, float]
    variations: Sequence[Variation] = ()
    zipped: bool = False
    windows: Optional[Sequence[Tuple[float, float]]] = None
    endTime: Optional[float] = None
    stepSize: Optional[float] = None
    source: str = ''
    maxSteps: Optional[int] = None
    checkStep: Optional[bool] = None
    points: StudyGrid = field(init=False, repr=False)
    _drive: Optional[Drive] = field(init=False, repr=False, default=None)

    def __post_init__(self):
        CheckParameterKeys(self.base, 'Study', 'base')
        self.base = dict(self.base)
        self.variations = list(self.variations)
        for v in self.variations:
            if not isinstance(v, Variation):
                raise TypeError(f"Study: 'variations' must hold Variation objects (ParseVariation), "
                                f"got {type(v).__name__}")
        if self.endTime is not None:
            self.endTime = CheckPositive('Study', 'endTime', self.endTime, 's')
        if self.maxSteps is not None and (isinstance(self.maxSteps, bool) or not isinstance(self.maxSteps, int)
                                          or self.maxSteps < 1):
            raise ValueError(f"Study: 'maxSteps' must be a whole number >= 1 (solver steps), got {self.maxSteps!r}")
        if self.windows is not None:      # a window beyond endTime would be judged on its missing part
            self.windows = CheckWindows(self.windows, self.endTime, 'Study')
        if self.checkStep is not None and not isinstance(self.checkStep, bool):
            raise TypeError(f"Study: 'checkStep' must be True, False or None (by the linear margin), "
                            f"got {self.checkStep!r}")
        self.points = StudyGrid(self.variations, self.zipped, 'Study')      # no point is built here
        first = ApplyOverrides(self.base, self.points[0])          # unknown keys raise here
        for Chain in (DriveSideChain, LoadSideChain):   # a chain with a gap (J9 without J4) fails every run: refuse
            try:
                Chain(first)
            except ValueError as err:
                raise ValueError(f"Study: {err}; every run would fail (varied: {', '.join(self.keys) or 'none'})"
                                 ) from None
        if self.windows is None and not IsReelChangerDuty(first):   # the phases of the first point's duty
            self.windows = DefaultWindows(Drive.FromParameters(first), self.endTime, minLength=1e-3)

    @property
    def keys(self) -> List[str]:
        """The varied keys, in order."""
        return [v.key for v in self.variations]

    @property
    def numberOfWindows(self) -> int:
        """Windows evaluated per run."""
        return _NUMBER_OF_DEFAULT_WINDOWS if self.windows is None else len(self.windows)

    def Parameters(self, run: int) -> Dict[str, float]:
        """The full parameter set of point ``run`` (0-based)."""
        return ApplyOverrides(self.base, self.points[run])

    @property
    def drive(self) -> Drive:
        """The base set as a drive, made once (each point is a :meth:`~exudyn_worm.drive.wholedrive.Drive.Replace`
        of it)."""
        if self._drive is None:
            self._drive = Drive.FromParameters(self.base, where='Study')
        return self._drive

    def Task(self, run: int) -> RunTask:
        """The picklable work item of point ``run`` for
        :func:`~exudyn_worm.analysis.studies.studypoint.RunPoint`."""
        varied = dict(self.points[run])
        options = dict(windows=self.windows, endTime=self.endTime, stepSize=self.stepSize, maxSteps=self.maxSteps,
                       checkStep=self.checkStep)
        try:
            return RunTask(run, self.drive, varied, **options)
        except (ValueError, TypeError):
            pass
        try:        # a base that is a whole drive only with the point's values (e.g. the varied key missing in it)
            return RunTask(run, Drive.FromParameters(self.Parameters(run), where='Study'), {}, **options)
        except (ValueError, TypeError) as err:      # recorded as the run's failure, as any other
            return RunTask(run, None, varied, **options, error=' '.join(f"{type(err).__name__}: {err}".split()))

    def ToDict(self) -> Dict:
        """JSON-ready definition: base set, variations, pairing, windows, times, number of runs."""
        return {'base': dict(self.base), 'source': self.source,
                'variations': [v.ToDict() for v in self.variations], 'zipped': self.zipped,
                'windows': None if self.windows is None else [list(w) for w in self.windows],
                'endTime': self.endTime, 'stepSize': self.stepSize, 'maxSteps': self.maxSteps,
                'checkStep': self.checkStep, 'runs': len(self.points)}

    def Identity(self) -> Dict:
        """What must match for a results file to be resumed: the definition without its free-text parts."""
        return _Identity(self.ToDict())


def ParseShard(text: Union[str, Tuple[int, int], None]) -> Optional[Tuple[int, int]]:
    """Parse ``'i/N'`` (0 <= i < N), e.g. ``'$SLURM_ARRAY_TASK_ID/4'`` expanded to ``'2/4'``.

    Parameters
    ----------
    text : str, (int, int) or None
        The shard; None means the whole study.

    Returns
    -------
    (int, int) or None

    Raises
    ------
    ValueError
        Unless 0 <= i < N.
    """
    if text is None:
        return None
    if isinstance(text, str):
        i, sep, n = text.partition('/')
        try:
            i, n = int(i), int(n)
        except ValueError:
            raise ValueError(f"ParseShard: expected 'i/N' with whole numbers 0 <= i < N (e.g. '0/4'), "
                             f"got {text!r}") from None
    else:
        i, n = text
    if not (isinstance(i, int) and isinstance(n, int) and 0 <= i < n):
        raise ValueError(f"ParseShard: a shard i/N needs whole numbers 0 <= i < N, got {text!r}")
    return i, n


def ShardIndices(numberOfRuns: int, shard: Optional[Tuple[int, int]]) -> List[int]:
    """Run indices of one shard: every N-th run starting at i (round robin, so shards get similar mixes).

    Parameters
    ----------
    numberOfRuns : int
        Runs in the whole study.
    shard : (int, int) or None
        ``(i, N)`` from :func:`ParseShard`; None for all runs.
    """
    if shard is None:
        return list(range(numberOfRuns))
    i, n = shard
    return list(range(i, numberOfRuns, n))


def ShardSize(numberOfRuns: int, shard: Optional[Tuple[int, int]]) -> int:
    """The number of runs of one shard, ``len(ShardIndices(numberOfRuns, shard))``, without building the list.

    Parameters
    ----------
    numberOfRuns : int
        Runs in the whole study.
    shard : (int, int) or None
        ``(i, N)`` from :func:`ParseShard`; None for all runs.

    Returns
    -------
    int
    """
    return numberOfRuns if shard is None else len(range(shard[0], numberOfRuns, shard[1]))


def CheckStudySize(study: 'Study', shard: Optional[Tuple[int, int]] = None, maxRuns: Optional[int] = None,
                   where: str = 'RunStudy', names: Tuple[str, str] = ('maxRuns', 'shard')) -> int:
    """Refuse a study (or shard) of more than ``maxRuns`` runs before any run or list of runs is built.

    Parameters
    ----------
    study : Study
        The study (its points are not built: :class:`StudyGrid`).
    shard : (int, int), optional
        ``(i, N)`` from :func:`ParseShard`; None for the whole study.
    maxRuns : int, optional
        Runs one call may hold, >= 1 (default :data:`MAX_RUNS`).
    where : str
        Prefix of the message.
    names : (str, str)
        How the message names the limit and the shard (``('--max-runs', '--shard')`` on the command line).

    Returns
    -------
    int
        The runs of this call.

    Raises
    ------
    ValueError
        Above the limit: the message says the size, the limit and into how many shards the study must be split.
    """
    limit = MAX_RUNS if maxRuns is None else maxRuns
    if isinstance(limit, bool) or not isinstance(limit, int) or limit < 1:
        raise ValueError(f"{where}: '{names[0]}' must be a whole number >= 1 (runs), got {maxRuns!r}")
    total = len(study.points)
    runs = ShardSize(total, shard)
    if runs <= limit:
        return runs
    shards = -(-total // limit)
    what = (f"the study has {total:,} runs ({study.points.Shape()})" if shard is None else
            f"shard {shard[0]}/{shard[1]} has {runs:,} of the study's {total:,} runs ({study.points.Shape()})")
    raise ValueError(f"{where}: {what}, above the limit of {limit:,} runs per call ({names[0]}; the parent holds "
                     f"about {BYTES_PER_RUN // 1000} kB per run: {runs * BYTES_PER_RUN / 1e9:,.1f} GB); split it into "
                     f"at least {shards:,} shards, one call each with its own output: {names[1]} i/{shards} for "
                     f"i = 0 ... {shards - 1} (a job array; ReadResults joins the files), or raise {names[0]}")


def _Identity(definition: Mapping) -> Dict:
    d = json.loads(json.dumps(definition))
    d.pop('source', None)
    d.setdefault('maxSteps', None)           # files written before the option existed: the default limit
    d.setdefault('checkStep', None)
    for v in d.get('variations', []):
        v.pop('text', None)
    return d

"""The files of a parameter study: the CSV results table (written a row at a time, read back and repaired after an
interrupt), its JSON sidecar with the definition and provenance (versions, git commit), the check of an output file
before a study starts (resume or refuse), and :class:`StudyResult`, the table read back."""
from __future__ import annotations

import csv
import json
import os
import platform
import subprocess
import time
import warnings
from dataclasses import dataclass
from importlib import metadata
from pathlib import Path
from typing import Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from ..._files import LockPath, WriteAtomically, WriteTextAtomically
from ...drive.presets import PARAMETER_UNITS
from ...items.results import CHATTER_STATES, UNDECIDED
from ..stability.drivestability import CHATTER, DIVERGENCE
from .studymap import ComputeChatterMap
from .studygrid import ShardIndices, Study, Variation, _Identity
from .studypoint import HALF_STEP_METRICS, RUN_COLUMNS, WINDOW_METRICS

__all__ = ['StudySidecarPath', 'ReadResults', 'StudyResult', 'StudyFileWarning']


_BOOL_COLUMNS = {'analyticStable', 'analyticStableLowering', 'loweringChatter', 'chatter', 'stepChecked'}
def _Columns(study: Study) -> List[str]:
    return list(RUN_COLUMNS) + study.keys + [f'w{i}.{name}' for i in range(study.numberOfWindows)
                                             for name in WINDOW_METRICS + tuple(f'halfStep.{m}' for m in
                                                                                HALF_STEP_METRICS)]


def _CsvText(value) -> str:
    if value is None:
        return ''
    if isinstance(value, float):
        return repr(value)
    return str(value)


def _FromCsv(column: str, text: str):
    if column in ('status', 'error'):
        return text
    if text == '':
        return None
    if column == 'run':
        return int(text)
    if column in ('analyticInstability', 'analyticInstabilityLowering'):
        if text not in (DIVERGENCE, CHATTER):
            raise ValueError(f"column {column}: expected {DIVERGENCE}, {CHATTER} or empty, got {text!r}")
        return text
    if column.endswith('.chatterState'):
        if text not in CHATTER_STATES:
            raise ValueError(f"column {column}: expected one of {', '.join(CHATTER_STATES)}, got {text!r}")
        return text
    if column in _BOOL_COLUMNS or column.endswith('.chatter'):
        verdict = column == 'loweringChatter' or column.endswith('.chatter')
        if text not in ('True', 'False') and not (verdict and text in ('unresolved', UNDECIDED)):
            raise ValueError(f"column {column}: expected True or False{', unresolved or undecided' if verdict else ''}"
                             f", got {text!r}")
        return text if text in ('unresolved', UNDECIDED) else text == 'True'
    return float(text)


def StudySidecarPath(output: Union[str, os.PathLike]) -> Path:
    """The JSON sidecar of a results file: ``runs.csv`` -> ``runs.study.json``.

    Parameters
    ----------
    output : str or path-like
        The CSV results file.
    """
    output = Path(output)
    return output.with_name(output.stem + '.study.json')


def _ReadCsv(path: Path, study: Optional[Study] = None, runs: Optional[Sequence[int]] = None,
             repair: bool = False) -> Tuple[List[str], List[Dict]]:
    """Rows of a results file. A line that cannot be read (cut off by a killed job, damaged, not UTF-8 text), or,
    given ``study``, that is no run of it (a run index outside the study or ``runs``, a varied parameter other than
    the study's own, every line of a run written twice) is dropped alone, not with the lines behind it; a warning
    names the dropped lines (the first five) and why. With ``repair`` the file is rewritten (atomically) without
    them, so that their runs are run again, but only if its header is the study's: a file that is refused is
    never written."""
    with path.open('rb') as f:
        raw = f.read()
    lines = raw.splitlines(keepends=True)
    try:
        header = next(csv.reader([lines[0].decode('utf-8')]), None) if lines else None
    except UnicodeDecodeError:
        header = ['(not UTF-8 text)']
    if header is None:
        return [], []
    if study is not None and header != _Columns(study):
        raise _HeaderError(header)
    allowed = None if runs is None else set(runs)
    rows, lineOf, keep, dropped = {}, {}, {}, []
    for number, line in enumerate(lines[1:], start=2):
        why = None
        try:
            text = line.decode('utf-8')
        except UnicodeDecodeError as err:
            dropped.append((number, f'not UTF-8 text ({err.reason} at byte {err.start})'))
            continue
        values = next(csv.reader([text]), [])
        if not line.endswith(b'\n'):
            dropped.append((number, 'cut off (no end of line: the job writing it was stopped)'))
            continue
        if len(values) != len(header):
            dropped.append((number, f'{len(values)} fields, expected {len(header)}'))
            continue
        try:
            row = {c: _FromCsv(c, v) for c, v in zip(header, values)}
            if row.get('run') is None:
                raise ValueError('column run: empty')
        except ValueError as err:
            dropped.append((number, str(err)))
            continue
        if study is not None:
            why = _NotARunOf(study, allowed, row)
        if why:
            dropped.append((number, why))
            continue
        if row['run'] in lineOf:
            first = lineOf[row['run']]
            if first in keep:
                dropped.append((first, f"run {row['run']} is written again on line {number} (both dropped)"))
                del keep[first]
                del rows[row['run']]
            dropped.append((number, f"run {row['run']} is written again (line {first}; both dropped)"))
            continue
        lineOf[row['run']] = number
        rows[row['run']] = row
        keep[number] = text
    if dropped:
        dropped.sort()
        shown = '; '.join(f'line {n}: {why}' for n, why in dropped[:5]) + (' ...' if len(dropped) > 5 else '')
        warnings.warn(f"'{path}': dropped {len(dropped)} line{'s' if len(dropped) > 1 else ''} that cannot be "
                      f"read or {'are' if len(dropped) > 1 else 'is'} no run of the study{', their runs are run again' if repair else ''} "
                      f"({shown})",
                      StudyFileWarning, stacklevel=3)
    if repair and dropped:
        WriteTextAtomically(path, lines[0].decode('utf-8') + ''.join(keep.values()))
    return header, [rows[k] for k in sorted(rows)]


def _SortByRun(path: Path) -> None:
    """Rewrite a results file (atomically) with its rows in run order: they are appended as the runs finish, in the
    order of completion, so that a stopped study keeps every finished run. The lines are kept as written; a file
    with a line cut off is left as it is (resuming it repairs it first)."""
    with path.open(newline='', encoding='utf-8', errors='replace') as f:
        lines = f.read().splitlines(keepends=True)
    if len(lines) < 3 or not all(line.endswith('\n') for line in lines):
        return
    column = next(csv.reader(lines[:1])).index('run')

    def Run(line: str) -> float:
        try:
            return int(next(csv.reader([line]))[column])
        except (ValueError, IndexError, StopIteration):
            return float('inf')                     # an unreadable line stays behind the readable ones

    body = sorted(lines[1:], key=Run)
    if body != lines[1:]:
        def Write(tmp: Path) -> None:
            with open(tmp, 'w', newline='', encoding='utf-8') as f:
                f.write(lines[0] + ''.join(body))
        WriteAtomically(path, Write)


class _HeaderError(ValueError):
    """A results file whose header is not the columns of the study (:func:`_ReadCsv`)."""

    def __init__(self, header: List[str]):
        super().__init__(header)
        self.header = header


def _NotARunOf(study: Study, allowed: Optional[set], row: Mapping) -> Optional[str]:
    """Why a row read back is no run of ``study`` (or of its shard, ``allowed``), or None if it is one."""
    run, size = row['run'], len(study.points)
    if not 0 <= run < size:
        return f'run {run} is no run of the study (runs 0 to {size - 1})'
    if allowed is not None and run not in allowed:
        return f'run {run} is no run of this shard'
    if row.get('status') not in ('ok', 'failed'):
        return f"status {row.get('status')!r}, expected ok or failed"
    point = study.points[run]
    for key in study.keys:
        if row.get(key) != point[key]:
            return f"run {run}: {key} = {_Text(row.get(key))}, but the study's run {run} has {key} = {_Text(point[key])}"
    return None


class StudyFileWarning(UserWarning):
    """A results file had lines that cannot be read (:func:`ReadResults`, a resumed study): they are dropped."""


def ReadResults(*paths: Union[str, os.PathLike]) -> 'StudyResult':
    """Read one or more results files of one study (e.g. the shards of a job array) into one result.

    Parameters
    ----------
    *paths : str or path-like
        CSV files written by :func:`RunStudy`, each with its JSON sidecar (:func:`StudySidecarPath`).

    Returns
    -------
    StudyResult
        The runs of all files, by run index (a run present twice is taken once, the last read).

    Raises
    ------
    ValueError
        If a file or sidecar is missing or the files belong to different studies.
    """
    if not paths:
        raise ValueError("ReadResults: give at least one results file")
    definition, rows = None, {}
    for path in map(Path, paths):
        sidecar = StudySidecarPath(path)
        if not path.is_file() or not sidecar.is_file():
            raise ValueError(f"ReadResults: '{path}' and its sidecar '{sidecar}' must both exist")
        try:
            meta = json.loads(sidecar.read_text(encoding='utf-8'))
            study = _StudyFromDict(meta['study'])
            same = definition is None or _Identity(meta['study']) == _Identity(definition)
        except (OSError, ValueError, KeyError, TypeError, AttributeError) as err:
            raise ValueError(f"ReadResults: its sidecar '{sidecar}' cannot be read ({type(err).__name__}: "
                             f"{' '.join(str(err).split())[:200]})") from None
        if not same:
            raise ValueError(f"ReadResults: '{path}' belongs to a different study than '{paths[0]}'")
        definition = definition or meta['study']
        try:
            found = _ReadCsv(path, study)[1]
        except _HeaderError:
            raise ValueError(f"ReadResults: '{path}' has other columns than its study (its header line was changed "
                             f"or lost)") from None
        for row in found:
            rows[row['run']] = row
    study = _StudyFromDict(definition)
    return StudyResult(study, [rows[k] for k in sorted(rows)])


#: the option of ``exudyn-worm sweep`` behind each entry of a study definition (for messages)
_DEFINITION_OPTIONS = {'base': '--preset/--config/--set', 'variations': '--vary', 'zipped': '--zip',
                       'windows': '--windows', 'endTime': '--end-time', 'stepSize': '--step-size',
                       'maxSteps': '--max-steps', 'checkStep': '--check-step/--no-check-step', 'runs': '--vary',
                       'shard': '--shard'}


def _Text(value) -> str:
    if value is None:
        return 'default'
    if isinstance(value, float):
        return f'{value:g}'
    return json.dumps(value)


def _DefinitionDifferences(old: Mapping, new: Mapping) -> List[str]:
    """What differs between two study identities (plus ``shard``), one phrase per entry: the entry, the
    option of ``sweep`` that sets it, the old and the new value."""
    out = []
    for name in dict.fromkeys(list(new) + list(old)):
        a, b = old.get(name), new.get(name)
        if a == b:
            continue
        option = _DEFINITION_OPTIONS.get(name, name)
        if name == 'base' and isinstance(a, Mapping) and isinstance(b, Mapping):
            for key in dict.fromkeys(list(b) + list(a)):
                if a.get(key) != b.get(key):
                    out.append(f"parameter {key} ({option}): {_Text(a.get(key))} in the file, {_Text(b.get(key))} now")
        elif name == 'variations' and isinstance(a, list) and isinstance(b, list):
            spell = lambda vs: '; '.join(f"{v.get('key')}={','.join(f'{x:g}' for x in v.get('values', []))}"
                                         for v in vs)
            out.append(f"varied values ({option}): {spell(a) or 'none'} in the file, {spell(b) or 'none'} now")
        elif name == 'runs' and old.get('variations') != new.get('variations'):
            continue                                      # the number of runs follows from the variations
        else:
            out.append(f"{name} ({option}): {_Text(a)} in the file, {_Text(b)} now")
    return out


def _StudyFromDict(d: Mapping) -> Study:
    return Study(base=d['base'], variations=[Variation(v['key'], tuple(v['values']), v.get('text', ''))
                                             for v in d['variations']],
                 zipped=d['zipped'], windows=d['windows'], endTime=d['endTime'], stepSize=d['stepSize'],
                 source=d.get('source', ''), checkStep=d.get('checkStep'))


@dataclass
class StudyResult:
    """The runs of a study, ordered by run index.

    Attributes
    ----------
    study : Study
        The definition.
    rows : list of dict
        Flat rows as in the CSV file (see :func:`RunPoint`).
    """
    study: Study
    rows: List[Dict]

    @property
    def finished(self) -> List[Dict]:
        """The rows of runs that succeeded (status ``ok``)."""
        return [r for r in self.rows if r['status'] == 'ok']

    @property
    def failed(self) -> List[Dict]:
        """The rows of failed runs."""
        return [r for r in self.rows if r['status'] != 'ok']

    @property
    def judged(self) -> List[Dict]:
        """The finished runs that :attr:`agreement` counts: a decided lowering window (chatter True or False) and a
        linear verdict of the lowering operating points that is not a divergence."""
        return [r for r in self._Decided() if r.get('analyticInstabilityLowering') != DIVERGENCE]

    def _Decided(self) -> List[Dict]:
        return [r for r in self.finished if r['loweringChatter'] in (True, False)
                and r['analyticStableLowering'] is not None]

    @property
    def divergent(self) -> List[Dict]:
        """The judged runs whose lowering points diverge (left out of :attr:`agreement`)."""
        return [r for r in self._Decided() if r.get('analyticInstabilityLowering') == DIVERGENCE]

    @property
    def agreement(self) -> Optional[float]:
        """Fraction of finished runs whose chatter while lowering matches the analytical S = -1 verdict
        (chatter iff unstable), over the runs whose lowering window is decided; None if there is none. Runs whose
        verdict is ``'unresolved'`` (it changes at half the step) or ``'undecided'`` (the window is too short to
        tell a decaying vibration from chatter) are left out (:attr:`judged` counts the others), and so are runs
        whose lowering points diverge (a real eigenvalue: a runaway or creep, not chatter; :attr:`divergent`)."""
        judged = self.judged
        if not judged:
            return None
        return sum(r['loweringChatter'] == (not r['analyticStableLowering']) for r in judged) / len(judged)

    def Run(self, row: Mapping) -> Dict:
        """One row in the JSON form of ``exudyn-worm sweep --json``.

        Parameters
        ----------
        row : mapping
            A flat row of :attr:`rows`.
        """
        windows = []
        for i in range(self.study.numberOfWindows):
            if row.get(f'w{i}.t0') is None:
                break
            windows.append({name: row[f'w{i}.{name}'] for name in WINDOW_METRICS})
            if row.get('stepChecked'):
                windows[-1]['halfStep'] = {name: row.get(f'w{i}.halfStep.{name}') for name in HALF_STEP_METRICS}
        return {'run': row['run'], 'parameters': {k: row[k] for k in self.study.keys},
                'status': row['status'], 'error': row['error'] or None, 'seconds': row['seconds'],
                'solveSeconds': row['solveSeconds'], 'stepSize': row['stepSize'], 'windows': windows,
                'analyticStable': row['analyticStable'], 'analyticStableLowering': row['analyticStableLowering'],
                'analyticInstability': row.get('analyticInstability'),
                'analyticInstabilityLowering': row.get('analyticInstabilityLowering'),
                'loweringChatter': row['loweringChatter'], 'stepChecked': row.get('stepChecked')}

    def ToDict(self) -> Dict:
        """``{"runs": [...], "agreement": float or None}`` (the schema of ``exudyn-worm sweep --json``)."""
        return {'runs': [self.Run(r) for r in self.rows], 'agreement': self.agreement}

    def Values(self, column: str) -> np.ndarray:
        """One column over all rows as a float array (NaN where missing), e.g. ``'J1'`` or
        ``'w1.maxNormalForce'``.

        Parameters
        ----------
        column : str
            A column of the results table.
        """
        return np.array([np.nan if r.get(column) is None else float(r[column]) for r in self.rows])

    def plot(self, x: str, y: Optional[str] = None, metric: str = 'w1.maxAbsWheelAcceleration',
             resolution: int = 60, **kwargs):
        """Plot with :mod:`exudyn_worm.plotting.plot_study` (matplotlib is imported only there): ``metric`` against
        parameter ``x``, or, with ``y``, the chatter map over ``x`` and ``y`` over the analytical region of
        :func:`~exudyn_worm.analysis.studies.studymap.ComputeChatterMap`.

        Parameters
        ----------
        x : str
            Varied key on the horizontal axis.
        y : str, optional
            Second varied key: draw the 2-D chatter map.
        metric : str, optional
            Column for the 1-D plot.
        resolution : int, optional
            Points per axis of the chatter map's analytical grid (the stability chart gets at least 300).
        **kwargs
            Passed on to the plotting function.

        Returns
        -------
        matplotlib.figure.Figure
        """
        from ...plotting import plot_study                   # lazy: matplotlib only when drawing
        if y is None:
            return plot_study.PlotMetric(self, x, metric, **kwargs)
        return plot_study.PlotChatterMap(self, ComputeChatterMap(self, x, y, resolution), **kwargs)


def _Versions(engine: str) -> Dict[str, str]:
    versions = {'python': platform.python_version(), 'platform': platform.platform()}
    for name in ('exudyn-worm', 'exudyn', 'numpy', 'scipy') + (('mpi4py',) if engine == 'mpi' else ()):
        try:
            versions[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            versions[name] = None
    try:                                                  # a source checkout: which commit computed the table
        git = ['git', '-C', str(Path(__file__).resolve().parent)]
        head = subprocess.run(git + ['rev-parse', 'HEAD'], capture_output=True, text=True, timeout=10)
        if head.returncode == 0:
            dirty = subprocess.run(git + ['status', '--porcelain', '--untracked-files=no'], capture_output=True,
                                   text=True, timeout=10)
            versions['gitCommit'] = head.stdout.strip()
            versions['gitModified'] = bool(dirty.stdout.strip())
    except (OSError, ValueError, subprocess.SubprocessError):
        pass
    return versions


def _CheckOutputPath(output: Path) -> None:
    """Check that the results file can be written (before it is locked and read)."""
    where = 'RunStudy'
    if output.suffix.lower() != '.csv':
        raise ValueError(f"{where}: 'output' must be a .csv file, got '{output}'")
    if output.is_dir():
        raise ValueError(f"{where}: 'output' is a directory: '{output}'")
    if not output.parent.is_dir():
        raise ValueError(f"{where}: the folder of 'output' does not exist: '{output.parent}'")
    if not os.access(output.parent, os.W_OK):
        raise ValueError(f"{where}: cannot write into '{output.parent}'")
    for path, what in ((StudySidecarPath(output), 'its sidecar'),
                       (LockPath(output), 'its lock file')):
        if path.is_dir():
            raise ValueError(f"{where}: the path of {what} '{path}' is a folder; move it away or choose another "
                             f"output file")
        if path.exists() and not path.is_file():
            raise ValueError(f"{where}: the path of {what} '{path}' is not a regular file; move it away or choose "
                             f"another output file")
    if output.exists() and not output.is_file():
        raise ValueError(f"{where}: 'output' is not a regular file: '{output}'")


def _CheckOutput(output: Path, study: Study, shard, overwrite: bool) -> List[Dict]:
    """Check the results file (checked by :func:`_CheckOutputPath` and locked) before computing; return the rows
    of a study to resume (else [])."""
    where = 'RunStudy'
    sidecar = StudySidecarPath(output)
    if overwrite or not output.exists():
        for p in (output, sidecar):
            if p.exists():
                p.unlink()
        return []
    if not sidecar.is_file():
        raise ValueError(f"{where}: '{output}' exists without its sidecar '{sidecar.name}', so it cannot be "
                         f"resumed; choose another output file or start it afresh (--overwrite; overwrite=True)")
    try:
        meta = json.loads(sidecar.read_text())
        old = dict(_Identity(meta['study']), shard=meta.get('shard') and list(meta['shard']))
        differences = _DefinitionDifferences(old, dict(study.Identity(), shard=shard and list(shard)))
    except (ValueError, KeyError, TypeError, AttributeError):
        differences = [f"its sidecar '{sidecar.name}' cannot be read"]
    if differences:
        raise ValueError(f"{where}: '{output}' holds results of a different study ({'; '.join(differences)}); "
                         f"give the same options to resume it, or choose another output file or start it afresh "
                         f"(--overwrite; overwrite=True)")
    try:
        return _ReadCsv(output, study, ShardIndices(len(study.points), shard), repair=True)[1]
    except _HeaderError as err:                           # refused before anything is written
        expected = _Columns(study)
        differ = next((f"column {i + 1} is {name!r}, expected {want!r}" for i, (name, want) in
                       enumerate(zip(err.header, expected)) if name != want),
                      f"{len(err.header)} columns, expected {len(expected)}")
        raise ValueError(f"{where}: '{output}' has other columns than this study ({differ}: its header line was "
                         f"changed or lost), so it cannot be resumed; the file is left as it is; choose another "
                         f"output file") from None


def _WriteSidecar(path: Path, study: Study, shard, engine, workers, started, versions, counts=None,
                  wallSeconds=None) -> None:
    meta = {'study': study.ToDict(), 'shard': list(shard) if shard else None, 'engine': engine, 'workers': workers,
            'versions': versions,
            'units': {k: PARAMETER_UNITS[k] for k in study.keys},
            'windowMetricUnits': {'t0': 's', 't1': 's', 'maxAbsWheelAcceleration': 'rad/s^2', 'maxNormalForce': 'N',
                                  'dominantFrequencyHz': 'Hz', 'fractionSNegative': '-', 'minWormSpeed': 'rad/s',
                                  'chatter': 'bool or undecided', 'chatterState': '-', 'chatterAmplitude': '-',
                                  'envelopeRate': '1/s', 'vibrationSeconds': 's'},
            'columns': _Columns(study), 'started': started, 'updated': time.strftime('%Y-%m-%dT%H:%M:%S%z'),
            'counts': counts, 'wallSeconds': wallSeconds}
    WriteTextAtomically(path, json.dumps(meta, indent=2, allow_nan=False))



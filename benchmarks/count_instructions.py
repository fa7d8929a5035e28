"""Instructions of the solver call alone, ours against the tuned LSODA model: P1 and P7 under callgrind.

Time on a shared machine moves by tens of percent with the load; instruction counts do not. For each model and
preset this runs one process under ``valgrind --tool=callgrind`` that counts only the solver call that
``bench_speed.py`` times: ``SolveDynamicInChunks`` inside ``SimulateReelChanger`` (ours, the defaults) and
``solve_ivp`` inside ``scipy_reference.SolveReelChangerScipy`` (LSODA, rtol 1e-5, atol 1e-8), each with everything
it calls (Exudyn's C++, the Python user and post-Newton functions; LSODA's Fortran and the Python right-hand side).

How only that call is counted: callgrind collects inside the C library's ``qsort`` alone
(``--toggle-collect='qsort*'``), and the solver is called from the comparison function of a ``qsort`` of two
integers (``ctypes``); the trampoline itself costs about 7,000 instructions. Nothing else in these processes calls
``qsort``: a run with the trampoline around nothing counts the same 7,000 (``--solve none``).

Usage::

    python benchmarks/count_instructions.py [--json FILE]          # four processes under valgrind, 5-10 min
    python benchmarks/count_instructions.py --solve ours reel-P1    # one solve in this process (what valgrind runs)
    python benchmarks/count_instructions.py --3d    # P1's 3D model, elastic bearings: small-displacement, exact, one-angle

Needs valgrind on PATH. Nothing is written unless ``--json FILE`` is given (callgrind's output goes to a temporary
folder that is removed).
"""
from __future__ import annotations

import argparse
import ctypes
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Callable, Dict, Optional, Sequence

sys.dont_write_bytecode = True                       # leave no __pycache__ beside the benchmark
HERE = Path(__file__).resolve().parent

__all__ = ['MODELS', 'PRESETS', 'Trampoline', 'SolveOnce', 'CountInstructions', 'Main']

MODELS = ('ours', 'lsoda')
PRESETS = ('reel-P1', 'reel-P7')
#: the 3D model of a preset with the bearings of examples/drives/reel-3d.toml (``--3d``): its small-displacement model
#: (the default of a drive with both shafts' bearings) and the exact rigid-body model, against the one-angle model
MODELS_3D = ('ours', 'small3d', 'exact3d')
DRIVE_3D = HERE.parent / 'examples' / 'drives' / 'reel-3d.toml'

_COMPARE = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_void_p, ctypes.c_void_p)


def Trampoline(function: Callable) -> Callable:
    """``function`` wrapped so that it runs inside the C library's ``qsort`` (what callgrind collects)."""
    libc = ctypes.CDLL(None)

    def Wrapped(*args, **kwargs):
        box = []

        def Compare(a, b):
            if not box:
                box.append(function(*args, **kwargs))
            return 0
        pair = (ctypes.c_int * 2)(1, 2)
        libc.qsort(pair, 2, ctypes.sizeof(ctypes.c_int), _COMPARE(Compare))
        return box[0]
    return Wrapped


def SolveOnce(model: str, preset: str) -> None:
    """One solve of ``preset`` by ``model`` ('ours', 'lsoda', 'small3d', 'exact3d' or 'none') with its solver call in
    the trampoline ('small3d', 'exact3d': the preset with the bearings of examples/drives/reel-3d.toml)."""
    sys.path.insert(0, str(HERE))
    import exudyn as exu                                         # lazy: a benchmark script's own process
    from exudyn_worm.drive.presets import GetPreset
    from exudyn_worm.drive.wholedrive import ResolveDrive
    import exudyn_worm.analysis.simulation.reelchanger as reelchanger
    import scipy_reference
    from bench_speed import SCIPY_SETTINGS
    exu.config.printToConsole = False
    p = GetPreset(preset)
    if model == 'ours':
        reelchanger.SolveDynamicInChunks = Trampoline(reelchanger.SolveDynamicInChunks)
        reelchanger.SimulateReelChanger(ResolveDrive(preset), progress=False)
    elif model in ('small3d', 'exact3d'):
        import functools                                         # lazy: a benchmark script's own process
        from exudyn_worm.builders.rigidbody import BuildRigidBodyReelChanger
        bearings = {k: v for k, v in ResolveDrive(config=str(DRIVE_3D)).parameters.items() if k not in GetPreset('reel-P1')}
        reelchanger.BuildRigidBodyReelChanger = functools.partial(BuildRigidBodyReelChanger, model=model[:-2])
        reelchanger.SolveDynamicInChunks = Trampoline(reelchanger.SolveDynamicInChunks)
        reelchanger.SimulateReelChanger(ResolveDrive(parameters={**p, **bearings}), progress=False)
    elif model == 'lsoda':
        scipy_reference.solve_ivp = Trampoline(scipy_reference.solve_ivp)
        scipy_reference.SolveReelChangerScipy(p, **SCIPY_SETTINGS)
    else:
        Trampoline(lambda: None)()


def CountInstructions(model: str, preset: str, valgrind: str = 'valgrind') -> int:
    """Instructions of one solver call (callgrind's total with the trampoline), in a new process.

    Parameters
    ----------
    model : str
        'ours', 'lsoda' or 'none' (the trampoline alone).
    preset : str
        'reel-P1' or 'reel-P7'.
    valgrind : str, optional
        The valgrind executable.

    Returns
    -------
    int
    """
    with tempfile.TemporaryDirectory() as folder:
        out = Path(folder) / 'solve.cg'
        # sys.executable, the interpreter's binary (or a link to it): valgrind follows no exec of a wrapper script
        env = {**os.environ, 'PYTHONHASHSEED': '0', 'PYTHONPATH': os.pathsep.join(
            [str(HERE.parent), *filter(None, [os.environ.get('PYTHONPATH')])])}
        subprocess.run([valgrind, '--tool=callgrind', f'--callgrind-out-file={out}', "--toggle-collect=qsort*",
                        sys.executable, str(Path(__file__).resolve()), '--solve', model, preset],
                       check=True, env=env, capture_output=True, text=True)
        match = re.search(r'^totals:\s+(\d+)', out.read_text(), re.MULTILINE)
        if match is None:
            raise RuntimeError(f'count_instructions: no totals in the callgrind output of {model} {preset}')
        return int(match.group(1))


def Main(argv: Optional[Sequence[str]] = None) -> Dict:
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--solve', nargs=2, metavar=('MODEL', 'PRESET'),
                        help="solve once in this process (what valgrind runs): MODEL 'ours', 'lsoda' or 'none'")
    parser.add_argument('--json', metavar='FILE', help='save the counts to FILE (JSON)')
    parser.add_argument('--3d', dest='threeD', action='store_true',
                        help="P1's 3D model with elastic bearings (small-displacement and exact) against the one-angle "
                             "model instead of ours against LSODA")
    args = parser.parse_args(argv)
    if args.solve:
        SolveOnce(*args.solve)
        return {}
    valgrind = shutil.which('valgrind')
    if valgrind is None:
        parser.error('valgrind is not on PATH')
    if args.threeD:
        counts = {model: CountInstructions(model, 'reel-P1', valgrind) for model in MODELS_3D}
        data = {'reel-P1': counts}
        for model in MODELS_3D[1:]:
            print(f"reel-P1 {model}: {counts[model] / 1e6:.1f} M instructions, one-angle {counts['ours'] / 1e6:.1f} M: "
                  f"x{counts[model] / counts['ours']:.2f}", flush=True)
        if args.json:
            Path(args.json).write_text(json.dumps(data, indent=1))
        return data
    data = {'trampoline': CountInstructions('none', 'reel-P1', valgrind)}
    for preset in PRESETS:
        counts = {model: CountInstructions(model, preset, valgrind) for model in MODELS}
        data[preset] = {**counts, 'ratio': counts['lsoda'] / counts['ours']}
        print(f"{preset}: ours {counts['ours'] / 1e6:.1f} M instructions, LSODA {counts['lsoda'] / 1e6:.1f} M: "
              f"x{data[preset]['ratio']:.1f}", flush=True)
    print(f"the trampoline alone: {data['trampoline']} instructions")
    if args.json:
        Path(args.json).write_text(json.dumps(data, indent=1))
        print(f"wrote {Path(args.json).resolve()}", file=sys.stderr)
    return data


if __name__ == '__main__':
    Main()

import sys, os, textwrap
from exudyn_worm.setups.wholedrive import ResolveDrive
P1 = open('/work/wt/units/examples/drives/reel-P1.toml').read()
HO = open('/work/wt/units/examples/drives/hoist.toml').read()
def sub(text, old, new):
    assert old in text, old
    return text.replace(old, new)
cases = {
 'mu>static': (HO, 'staticFrictionCoefficient = 0.12', 'staticFrictionCoefficient = 0.05'),
 'z1 frac': (HO, 'starts = 1 ', 'starts = 1.5 '),
 'gamma+rho': (P1, 'frictionCoefficient = 0.132', 'frictionCoefficient = 12'),
 'u<1': (P1, 'wheelRadius = "105.95 mm"', 'wheelRadius = "1.5 mm"'),
 'overflow J1': (P1, 'inertia = "0.1 kg*m^2"', 'inertia = "1e-300 kg*m^2"'),
 'overflow kT': (P1, 'stiffness = "7000 N*m/rad"', 'stiffness = "1e300 N*m/rad"'),
 'no mu': (P1, 'frictionCoefficient = 0.132 ', '#'),
 'no DV': (P1, 'meshDampingMeasure = 0.014 ', '#'),
 'no DT': (P1, 'dampingMeasure = 0.014 ', '#'),
 'kA no mA': (P1, '[motor]', '[axialBearing]\nstiffness = "1e8 N/m"\n[motor]'),
 'stage no k': (P1, '[motor]', '[[driveSide]]\ninertia = "0.05 kg*m^2"\n[motor]'),
 'motor char missing': (P1, 'speed = "472.5 rpm"', 'type = "characteristic"\nstallTorque = "100 N*m"'),
 'startStop brake<ramp': (P1, 'speed = "472.5 rpm"', 'type = "startStop"\nspeed = "472.5 rpm"\nrampTime = "1 s"\nbrakeTime = "0.5 s"'),
 'table file missing': (HO, 'type = "constant"\ntorque = "-367.875 N*m"', 'type = "timeTable"\ntorqueOverTime = "nofile.csv"'),
 'speed table decreasing': (HO, '[0.2, "100 rpm"], [1.2', '[0.2, "100 rpm"], [0.1'),
 'frictionTable bad': (HO, 'frictionLaw = "stribeck"', 'frictionLaw = "table"\nfrictionTable = [[0, 0.1], [0, 0.2]]'),
 'wormMass no bearing': (P1, '[wheel]', '[worm]\nmass = "3 kg"\n[wheel]'),
 'bearing no mass': (P1, '[motor]', '[wormBearing]\nradialStiffness = "1e8 N/m"\naxialStiffness = "1e8 N/m"\n[motor]'),
 'choice bad': (P1, '[load]', '[load]\ntype = "levr"'),
 'motor cannot carry': (P1, 'speed = "472.5 rpm"', 'type = "characteristic"\nstallTorque = "1 N*m"\nnoLoadSpeed = "100 rad/s"\ninertia = "0.01 kg*m^2"'),
 'mesh stiffness neg': (P1, 'meshStiffness = "2e8 N/m"', 'meshStiffness = "-2e8 N/m"'),
 'geometry mix': (P1, 'backlash = "0 mm"', 'backlash = "0 mm"\ncentreDistance = "124 mm"'),
 'geometry incomplete': (HO, 'wheelTeeth = 50 ', '#'),
 'chain gap': (P1, '[motor]', '[[driveSide]]\ninertia = "0.05 kg*m^2"\nstiffness = "1 N*m/rad"\n[[driveSide]]\ndamping = "1 N*m*s/rad"\n[motor]'),
 'loadSide neg': (HO, 'inertia = "6.2 kg*m^2"', 'inertia = "-6.2 kg*m^2"'),
 'DT overflow': (P1, 'dampingMeasure = 0.014', 'dampingMeasure = 1e300'),
}
for name, (base, old, new) in cases.items():
    path = f'/tmp/units_audit/{name.replace(" ", "_")}.toml'
    open(path, 'w').write(sub(base, old, new))
    try:
        d = ResolveDrive(config=path)
        from exudyn_worm.analysis.drivestability import AnalyzeDrive
        print(f'{name}: ACCEPTED')
    except Exception as e:
        print(f'{name}: {type(e).__name__}: {e}')
for name, kw in {'sets None': dict(preset='reel-P1', sets=None), 'sets int': dict(preset='reel-P1', sets=5),
                 'params list': dict(parameters=[1]), 'preset bad': dict(preset='nope'), 'config int': dict(config=5),
                 'sets bad item': dict(preset='reel-P1', sets=[5]), 'sets tuple bad key': dict(preset='reel-P1', sets=[('foo', 1)]),
                 'sets tuple bad val': dict(preset='reel-P1', sets=[('J1', 'abc')]), 'sets tuple range': dict(preset='reel-P1', sets=[('J1', -1.)]),
                 'params bad key': dict(parameters={'foo': 1}), 'params neg': dict(parameters={**__import__('exudyn_worm').GetPreset('reel-P1'), 'J1': -1.}),
                 'params str': dict(parameters={**__import__('exudyn_worm').GetPreset('reel-P1'), 'J1': '0.1'})}.items():
    try:
        ResolveDrive(**kw); print(f'{name}: ACCEPTED')
    except Exception as e:
        print(f'{name}: {type(e).__name__}: {e}')

"""The parameter registry (exudyn_worm.params.parameters): each key declared once, and everything derived from it.

The test-only keys below (``testLaw``, ``testSpeed``, ``testTable``, ...) stand for the friction-law keys:
a choice, a number in m/s and a table of (speed, mu) rows. They prove that a key declared in the registry alone
reaches --set, drive files, the checks, the messages and the docs.
"""
import copy
from pathlib import Path

import pytest

from exudyn_worm.drive.config import LoadConfig, ParseQuantity, ParseSetOption, ResolveParameters
from exudyn_worm.params.drivefile import DRIVE_FILE_TABLES, FileKeyOf, FlattenDriveFile
from exudyn_worm.params.parameters import PARAMETERS, Parameter, ParameterRegistry, ParametersMarkdown, WithGeneratedTables
from exudyn_worm.drive.presets import (PARAMETER_UNITS, ApplyOverrides, CheckParameterKeys, CheckParameters, GetPreset,
                                 UnknownParameterMessage)
from exudyn_worm.analysis.studies.studygrid import ParseVariation

DOCS = Path(__file__).resolve().parents[1] / 'docs'

TEST_KEYS = [
    Parameter('testLaw', kind='choice', choices=('constant', 'stribeck', 'agma', 'table'),
              description='test-only friction law', table='gear', fileKey='testFrictionLaw'),
    Parameter('testSpeed', 'm/s', 'positive', 'test-only Stribeck speed', table='gear', fileKey='testSpeed'),
    Parameter('testStatic', '', 'nonNegative', 'test-only static friction', table='gear', fileKey='testStatic'),
    Parameter('testTable', kind='table', columns=(('speed', 'm/s', 'nonNegative'), ('mu', '', 'nonNegative')),
              description='test-only friction table', table='gear', fileKey='testTable'),
    Parameter('testA', 'm', 'positive', 'test-only form A', quantity='test quantity'),
    Parameter('testB', '', 'nonNegative', 'test-only form B', quantity='test quantity'),
]


#: the package's keys before any test declared one (other branches add keys: no fixed count here)
_KEYS_AT_IMPORT = PARAMETERS.Keys()


@pytest.fixture
def declared():
    """Declare TEST_KEYS in the package's registry for one test, then restore it."""
    state = (dict(PARAMETERS._byName), dict(PARAMETERS._series), dict(PARAMETER_UNITS),
             copy.deepcopy(PARAMETERS.fileTables))
    for parameter in TEST_KEYS:
        PARAMETERS.Declare(parameter)
    yield
    byName, series, units, tables = state
    PARAMETERS._byName.clear(), PARAMETERS._byName.update(byName)
    PARAMETERS._series.clear(), PARAMETERS._series.update(series)
    dict.clear(PARAMETER_UNITS), dict.update(PARAMETER_UNITS, units)
    for table in list(PARAMETERS.fileTables):
        if table not in tables:
            del PARAMETERS.fileTables[table]
        else:
            PARAMETERS.fileTables[table].clear()
            PARAMETERS.fileTables[table].update(tables[table])


# -- the registry and what derives from it ------------------------------------------------------------------

def test_docs_page_is_generated_from_the_registry():
    assert (DOCS / 'parameters.md').read_text() == ParametersMarkdown(), \
        'docs/parameters.md is stale: run python -m exudyn_worm.params.parameters docs'


def test_drive_file_page_table_is_generated_from_the_registry():
    text = (DOCS / 'drive-files.md').read_text()
    assert '<!-- begin generated: drive-file-table -->' in text
    assert WithGeneratedTables(text) == text, 'docs/drive-files.md is stale: run python -m exudyn_worm.params.parameters docs'


def test_public_tables_derive_from_the_registry():
    assert list(PARAMETER_UNITS) == list(PARAMETERS.Keys())
    assert all(PARAMETER_UNITS[p.key] == p.unit for p in PARAMETERS)
    assert PARAMETER_UNITS['J12'] == 'kg*m^2' and 'J3' not in PARAMETER_UNITS and 'k0' not in PARAMETER_UNITS
    single = {(p.table, p.fileKey): p.key for p in PARAMETERS if p.table and not p.series}
    assert {(t, f): k for t, keys in DRIVE_FILE_TABLES.items() for f, k in keys.items()} == single


def test_every_parameter_reaches_its_drive_file_key_and_back():
    for p in PARAMETERS:
        if not p.table:
            continue
        value = 0.1 if p.range != 'finite' else 1.
        data = {p.table: [{p.fileKey: value}]} if p.series else {p.table: {p.fileKey: value}}
        _, values = FlattenDriveFile(data, 'test')
        assert [(k, v) for k, v, _ in values] == [(p.key, value)]
        assert FileKeyOf(p.key) == (f'[[{p.table}]] {p.fileKey}' if p.series else f'[{p.table}] {p.fileKey}')


def test_alternatives_of_the_three_quantities():
    assert PARAMETERS.Alternatives('mu') == ('rho',) and PARAMETERS.Alternatives('DV') == ('dV',)
    assert PARAMETERS.Alternatives('DTV') == ('dT', 'DT') and PARAMETERS.Alternatives('kT') == ()
    assert PARAMETERS.Quantity('rho') == 'flank friction' and PARAMETERS.Quantity('DT') == 'drive-shaft damping'
    assert PARAMETERS.Conflicts({'mu': 0.1, 'J1': 1., 'dT': 1., 'rho': 0.1, 'DTV': 2.}) == [
        ('mu', ('rho',)), ('dT', ('DTV',))]


def test_axis_labels():
    assert PARAMETERS.AxisLabel('backlash') == ('backlash [mm]', 1e3)
    assert PARAMETERS.AxisLabel('backlash', display=False) == ('backlash [m]', 1.)
    assert PARAMETERS.AxisLabel('DTV') == ('DTV [–]', 1.) and PARAMETERS.AxisLabel('k5')[0] == 'k5 [N*m/rad]'


def test_series_keys():
    assert PARAMETERS.SeriesIndex('d17') == ('d', 17) and PARAMETERS.SeriesIndex('J3') is None
    assert PARAMETERS.SeriesIndex('kA') is None and PARAMETERS.SeriesIndex(4) is None
    assert PARAMETERS['k9'] is PARAMETERS.Series('k')


@pytest.mark.messages
def test_declaring_twice_is_refused():
    with pytest.raises(ValueError, match="'kT' is declared already"):
        PARAMETERS.Declare(Parameter('kT', 'N*m/rad', 'positive'))
    with pytest.raises(ValueError, match=r"\[gear\] wormRadius is declared already"):
        ParameterRegistry([Parameter('a', table='gear', fileKey='wormRadius'),
                           Parameter('b', table='gear', fileKey='wormRadius')])
    with pytest.raises(ValueError, match="'J4' is declared already"):
        ParameterRegistry([Parameter('J4'), Parameter('J', series=4)])


@pytest.mark.messages
@pytest.mark.parametrize('kwargs, message', [
    (dict(name='x', kind='list'), "'kind' of 'x' must be one of number, choice, table"),
    (dict(name='x', range='big'), "'range' of 'x' must be one of"),
    (dict(name='x', kind='choice'), "the choice 'x' needs 'choices'"),
    (dict(name='x', kind='table', columns=(('v', 'm/s'),)), "the table 'x' needs 'columns'"),
    (dict(name='x', table='gear'), "'x' needs both 'table' and 'fileKey'"),
    (dict(name='1x'), "'name' must be an identifier"),
])
def test_bad_declarations(kwargs, message):
    with pytest.raises(ValueError, match=message.replace('(', r'\(').replace(')', r'\)')):
        Parameter(**kwargs)


# -- the kinds of value, in a registry of their own -----------------------------------------------------------

@pytest.fixture
def small():
    return ParameterRegistry(TEST_KEYS)


def test_number_kind(small):
    assert small.Parse('testSpeed', '3.6 km/h', 'w') == pytest.approx(1.0, rel=1e-12)
    assert small.Parse('testSpeed', 2, 'w') == 2.0
    with pytest.raises(ValueError, match=r"w: 'testSpeed' must be in m/s \(plain numbers are SI\), got '3 rad'"):
        small.Parse('testSpeed', '3 rad', 'w')
    with pytest.raises(ValueError, match=r"w: 'testSpeed' must be > 0 m/s, got -1 m/s"):
        small.Check('testSpeed', -1., 'w')
    assert small.Check('testStatic', 0., 'w') == 0.
    with pytest.raises(ValueError, match=r"w: 'testStatic' must be >= 0, got -0.1"):
        small.Check('testStatic', -0.1, 'w')


def test_choice_kind(small):
    assert small.Parse('testLaw', ' stribeck ', 'w') == 'stribeck'
    with pytest.raises(ValueError, match=r"w: 'testLaw' must be one of: constant, stribeck, agma, table, got "
                                         r"'strbeck' \(did you mean 'stribeck'\?\)"):
        small.Parse('testLaw', 'strbeck', 'w')
    with pytest.raises(ValueError, match=r"w: 'testLaw' must be one of: .*, got float 1.0"):
        small.Check('testLaw', 1.0, 'w')


def test_table_kind(small):
    rows = small.Parse('testTable', [[0, 0.12], ['0.5 m/s', '9 %'], [2, 0.05]], 'w')
    assert rows == ((0., 0.12), (0.5, pytest.approx(0.09, rel=1e-12)), (2., 0.05))
    assert small.Parse('testTable', '[[0, 0.1], [1, 0.05]]', 'w') == ((0., 0.1), (1., 0.05))
    assert small.Parse('testTable', ' friction.csv ', 'w') == 'friction.csv'
    with pytest.raises(ValueError, match=r"w: 'testTable\[1\] mu' must be >= 0, got -0.05"):
        small.Parse('testTable', [[0, 0.1], [1, -0.05]], 'w')
    with pytest.raises(ValueError, match=r"w: 'testTable': the speed must increase from row to row, got 1 then 1"):
        small.Parse('testTable', [[0, 0.1], [1, 0.05], [1, 0.04]], 'w')
    with pytest.raises(ValueError, match=r"w: 'testTable': row 0 must hold 2 values \(speed, mu\), got \[0\]"):
        small.Parse('testTable', [[0]], 'w')
    with pytest.raises(ValueError, match=r"w: 'testTable' must have at least one row"):
        small.Parse('testTable', [], 'w')
    with pytest.raises(ValueError, match=r"w: 'testTable\[0\] speed' must be in m/s"):
        small.Parse('testTable', [['1 deg', 0.1]], 'w')
    with pytest.raises(ValueError, match=r"w: 'testTable': cannot read the array"):
        small.Parse('testTable', '[[0, 0.1]', 'w')
    with pytest.raises(TypeError, match=r"w: 'testTable' must be a file path or rows of 2 values"):
        small.Check('testTable', 3.0, 'w')


def test_alternative_forms_in_a_small_registry(small):
    assert small.Alternatives('testA') == ('testB',)
    assert small.Conflicts({'testB': 1., 'testSpeed': 1., 'testA': 2.}) == [('testB', ('testA',))]


def test_markdown_of_the_kinds(small):
    table = small.MarkdownTable()
    assert '| `testLaw` | – | one of: constant, stribeck, agma, table | `[gear] testFrictionLaw` |' in table
    assert '| `testTable` | – | file path, or rows (speed m/s >= 0, mu – >= 0) | `[gear] testTable` |' in table
    assert '`testA` | m | > 0 | – | test-only form A (or give `testB`: one form of the test quantity) |' in table


# -- a key declared in the registry alone reaches --set, drive files, checks, errors and docs ---------------------

def test_declared_key_reaches_set_option(declared):
    assert ParseSetOption('testSpeed=3.6 km/h') == ('testSpeed', pytest.approx(1.0, rel=1e-12))
    assert ParseSetOption('testLaw=agma') == ('testLaw', 'agma')
    assert ParseSetOption('testTable=[[0, 0.1], [1, 0.05]]') == ('testTable', ((0., 0.1), (1., 0.05)))
    assert ParseQuantity('testStatic', '15 %') == pytest.approx(0.15, rel=1e-12)
    p = ResolveParameters('reel-P1', sets=['testLaw=stribeck', 'testSpeed=0.1', 'testA=2 mm'])
    assert p['testLaw'] == 'stribeck' and p['testSpeed'] == 0.1 and p['testA'] == 0.002
    with pytest.raises(ValueError, match=r"both 'testB' and 'testA' are given, which describe the same quantity"):
        ResolveParameters('reel-P1', sets=['testB=1', 'testA=2 mm'])
    with pytest.raises(ValueError, match=r"'testLaw' must be one of: constant, stribeck, agma, table, got 'coulomb'"):
        ResolveParameters('reel-P1', sets=['testLaw=coulomb'])


def test_declared_key_reaches_drive_files(declared, tmp_path):
    path = tmp_path / 'drive.toml'
    path.write_text('preset = "reel-P1"\n[gear]\ntestFrictionLaw = "table"\ntestSpeed = "2 mm/s"\n'
                    'testTable = [[0, 0.12], ["1 m/s", 0.05]]\n')
    config = LoadConfig(path)
    assert config['parameters'] == {'testLaw': 'table', 'testSpeed': pytest.approx(0.002, rel=1e-12),
                                    'testTable': ((0., 0.12), (1., 0.05))}
    assert FileKeyOf('testLaw') == '[gear] testFrictionLaw'
    path.write_text('preset = "reel-P1"\n[gear]\ntestSpeed = "-2 mm/s"\n')
    with pytest.raises(ValueError, match=r"line 3: \[gear\] testSpeed: 'testSpeed' must be > 0 m/s, got -0.002 m/s"):
        LoadConfig(path)
    path.write_text('preset = "reel-P1"\n[gear]\ntestFrictionLw = "table"\n')
    with pytest.raises(ValueError, match=r"unknown key 'testFrictionLw' \(did you mean 'testFrictionLaw'\?\)"):
        LoadConfig(path)


@pytest.mark.messages
def test_declared_key_reaches_checks_and_messages(declared):
    base = GetPreset('reel-P1')
    CheckParameters({**base, 'testLaw': 'agma', 'testTable': 'mu.csv'})
    with pytest.raises(ValueError, match=r"parameter set: 'testSpeed' must be > 0 m/s, got 0 m/s"):
        CheckParameters({**base, 'testSpeed': 0.})
    with pytest.raises(ValueError, match=r"unknown parameter 'testlaw' \(did you mean 'testLaw'\?\); expected one "
                                         r"of: .* mA .* wheelBearingSpan testLaw testSpeed"):
        CheckParameterKeys({**base, 'testlaw': 'agma'}, 'f')
    assert 'testLaw' in UnknownParameterMessage('f', 'x')
    with pytest.raises(ValueError, match=r"'testA' and 'testB' are given together, which describe the same quantity "
                                         r"\(test quantity\)"):
        CheckParameterKeys({'testA': 1., 'testB': 1.})
    assert ApplyOverrides({**base, 'testA': 1.}, {'testB': 2.})['testB'] == 2.


def test_declared_key_reaches_the_docs(declared):
    text = ParametersMarkdown()
    assert '| `testSpeed` | m/s | > 0 | `[gear] testSpeed` | test-only Stribeck speed |' in text
    page = WithGeneratedTables((DOCS / 'drive-files.md').read_text())
    assert '| | `testFrictionLaw` | `testLaw` | test-only friction law | – |' in page


def test_registry_restored_after_the_declarations():
    assert 'testLaw' not in PARAMETER_UNITS and 'testFrictionLaw' not in DRIVE_FILE_TABLES['gear']
    assert PARAMETERS.Keys() == _KEYS_AT_IMPORT and PARAMETERS.Get('testLaw') is None


def test_a_study_sweeps_numbers_only(declared):
    assert list(ParseVariation('testSpeed=1,2 mm/s').values) == [1., 0.002]
    with pytest.raises(ValueError, match=r"ParseVariation: 'testLaw=agma,table': a study sweeps numbers; 'testLaw' "
                                         r"takes a choice \(one of: constant, stribeck, agma, table\)"):
        ParseVariation('testLaw=agma,table')
    with pytest.raises(ValueError, match=r"ParseVariation: 'testlaw=1': unknown parameter 'testlaw' \(did you mean "
                                         r"'testLaw'\?\)"):
        ParseVariation('testlaw=1')

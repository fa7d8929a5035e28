"""exudyn-worm: worm-gear chatter analysis and simulation for Exudyn."""
from .gear import WormGear
from .drive import (ElasticDrive, MeshDampingFromMeasure, MeshDampingMeasure,
                    TorsionalDampingFromMeasure, TorsionalDampingMeasure)
from .stability import AnalyzeStability, StabilityAnalysis, ContactStability

__version__ = '0.1.0'

__all__ = ['WormGear', 'ElasticDrive', 'MeshDampingFromMeasure', 'MeshDampingMeasure',
           'TorsionalDampingFromMeasure', 'TorsionalDampingMeasure', 'AnalyzeStability',
           'StabilityAnalysis', 'ContactStability', '__version__']

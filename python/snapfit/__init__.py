"""snapfit from Python: scenes, assemblies and queries with numpy arrays.

    import numpy as np, snapfit
    assembly = snapfit.Assembly(snapfit.load_scene("scenes/default.json"))
    engine = assembly.query_engine()
    engine.modes = 4096
    r = engine.query(np.array([[0, 0, 25, 1, 0, 0, 0]]))   # x, y, z, qw, qx, qy, qz
    r["energy"], r["force"], r["torque"]
"""
import json as _json

from ._snapfit import (Assembly, Error, LiveSession, QueryEngine, Scene, accuracy, auto_tune, load_scene, part_fields,
                       part_mesh, run_job, search)
from ._snapfit import _parse_scene

__all__ = ["Assembly", "Error", "LiveSession", "QueryEngine", "Scene", "accuracy", "auto_tune", "load_scene", "part_fields",
           "part_mesh", "run_job", "scene_from_dict", "search"]


def scene_from_dict(scene: dict, origin: str = "<dict>") -> Scene:
    """A scene from a dict with the scene file's schema (docs/scenes.md); raises
    snapfit.Error naming the field that is wrong, as for a file. Relative paths are
    taken from the current folder."""
    return _parse_scene(_json.dumps(scene), origin)

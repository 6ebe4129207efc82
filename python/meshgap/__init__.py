# The package meshgap: the compiled extension meshgap._meshgap, every public name of it re-exported here with its
# docstring; meshgap.distributed runs the batch on Dask (imported on demand: it needs python3-dask), and
# meshgap.campaign benchmark campaigns on it (meshgap.campaign, imported on first use).
from . import _meshgap
from ._meshgap import *  # noqa: F401,F403  (Scene, load_mesh, plan, PLAN_KEYWORDS, SCENE_BATCH_BLOCK, ...)

__doc__ = _meshgap.__doc__
__all__ = [name for name in dir(_meshgap) if not name.startswith("_")]
for _name in __all__:
    _value = getattr(_meshgap, _name)
    if getattr(_value, "__module__", None) == _meshgap.__name__:
        try:
            _value.__module__ = __name__  # meshgap.Scene, as before, in help() and reprs
        except (AttributeError, TypeError):
            pass
del _name, _value


def __getattr__(name):
    """meshgap.campaign on first use, so `python3 -m meshgap.campaign` runs it as a fresh module."""
    if name == "campaign":
        import importlib
        return importlib.import_module(".campaign", __name__)
    raise AttributeError("module %r has no attribute %r" % (__name__, name))

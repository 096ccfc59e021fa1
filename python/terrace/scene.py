"""terrace.Scene: a scene checked by the command line's own reader."""

import json
import os
import warnings
from collections.abc import Mapping

from . import _terrace


def _json_value(value):
    """A value as JSON text, as ``--set key=VALUE`` takes it (NumPy scalars and arrays too)."""
    def plain(x):
        if hasattr(x, "tolist"):  # NumPy scalars and arrays
            return x.tolist()
        raise TypeError(f"a scene value must be JSON-like, got {type(x).__name__}")
    return json.dumps(value, allow_nan=False, default=plain)


class Scene:
    """A scene, read and checked by the same C++ reader as ``terrace run`` (same messages).

    Scene(source=None, overrides=None, *, strict=False, **keys)

    source     a scene file's path (str or os.PathLike); a dict of the scene's JSON; another
               Scene (its source and overrides, then these); None: the built-in default scene
               (the paper's dense rods).
    overrides  a dict of dotted scene keys and values, applied as ``terrace run --set`` applies
               them: {"state.n": 216, "smd.dt_fs": 1.8}.
    keys       top-level keys as keywords, the same: engine="smd", seed=3, name="x".
    strict     a key of the engine that does not run (smd.dt_fs on a DMD scene) is refused
               instead of warned about, as ``terrace run --strict``.

    Raises SceneError with the CLI's message ("<origin>: <key>: <problem>") on a bad key or
    value; a scene given as a dict is named "<scene dict>" in messages. Warnings (legal values
    that are probably not meant) are Python UserWarnings.
    """

    def __init__(self, source=None, overrides=None, *, strict=False, **keys):
        path, text, earlier = "", "", []
        if isinstance(source, Scene):
            path, text, earlier = source._path, source._text, list(source._sets)
        elif isinstance(source, (str, os.PathLike)):
            path = os.fspath(source)
        elif isinstance(source, Mapping):
            text = _json_value(dict(source))
        elif source is not None:
            raise TypeError("Scene takes a path, a dict, a Scene or None, got "
                            f"{type(source).__name__}")
        sets = dict(overrides or {})
        sets.update(keys)
        self._path, self._text = path, text
        self._sets = earlier + [f"{k}={_json_value(v)}" for k, v in sets.items()]
        self._scene = _terrace.resolve_scene(path, text, self._sets, strict)
        for w in self._scene.warnings:
            warnings.warn(w, UserWarning, stacklevel=2)

    def resolved(self):
        """The fully resolved scene as a dict, every key written out (the run's scene.json)."""
        return json.loads(self._scene.json)

    @property
    def name(self):
        """The scene's name."""
        return self.resolved()["name"]

    @property
    def engine(self):
        """The engine that runs it: "dmd" or "smd"."""
        return self.resolved()["engine"]

    @property
    def overrides(self):
        """The overrides as ``--set`` takes them ("key=value", the value as JSON)."""
        return list(self._sets)

    @property
    def default_output(self):
        """The directory ``terrace run`` would write into: out/<name>-<engine>[-<overrides>]."""
        return self._scene.default_output

    def cli_arguments(self):
        """The ``terrace run`` arguments of the same scene (the path and --set options).

        A scene from a dict has no file to name: write ``resolved()`` to one first."""
        if self._text:
            raise ValueError("a scene from a dict has no file: json.dump(scene.resolved(), f) "
                             "and run that")
        args = [self._path] if self._path else []
        for s in self._sets:
            args += ["--set", s]
        return args

    def __repr__(self):
        origin = self._path or ("<scene dict>" if self._text else "<built-in default scene>")
        return f"terrace.Scene({origin!r}, overrides={self._sets!r})"

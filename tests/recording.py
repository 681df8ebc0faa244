"""A stand-in for ``meshcat.Visualizer`` that records what a scene sends, with no server.

``log`` maps each path ("/a/b") to its current state (object, transform, properties, and how many
times an object was set there); ``calls`` lists every call in order as (method, path, ...).
Scene builders accept it through their ``vis=`` argument, like the injected transports of the
hardware drivers.
"""
import numpy as np
from meshcat.path import Path


class Recorder:
    """Records set_object/set_transform/set_property/set_animation/delete per path."""

    def __init__(self, log=None, calls=None, path=Path()):
        self.log = {} if log is None else log
        self.calls = [] if calls is None else calls
        self.path = path  # a meshcat Path, as meshcat's Animation expects

    def __getitem__(self, name):
        return Recorder(self.log, self.calls, self.path.append(name))

    @property
    def key(self) -> str:
        return self.path.lower()

    def _node(self):
        return self.log.setdefault(self.key, {})

    def set_object(self, geometry, material=None):
        node = self._node()
        node["object"] = (geometry, material)
        node["n_objects"] = node.get("n_objects", 0) + 1
        self.calls.append(("set_object", self.key))

    def set_transform(self, matrix=np.eye(4)):
        self._node()["transform"] = np.asarray(matrix)
        self.calls.append(("set_transform", self.key, np.array(matrix)))

    def set_property(self, key, value):
        self._node()[key] = value
        self.calls.append(("set_property", self.key))

    def set_animation(self, animation, play=True, repetitions=1):
        self.log["animation"] = animation
        self.calls.append(("set_animation", self.key))

    def delete(self):
        for key in [k for k in self.log if k == self.key or k.startswith(self.key + "/")]:
            del self.log[key]
        self.calls.append(("delete", self.key))

"""How a graded call crosses from the judge to the learner's kernel and back: plain data only.

The grader runs the package's checks in one process (the *judge*) and the learner's
code in another (their notebook's kernel, in its sandbox). A check calls the learner's
function through a proxy; the proxy sends the arguments over a Unix socket, the kernel
calls the real function and sends back its answer and the arguments as the function
left them (a flip changes its mesh in place). This module is the format of those
messages, used on both sides.

Why not pickle: unpickling runs code named by the data, and the kernel's side of the
socket is the learner's. Everything here is JSON with a few tagged shapes::

    {"t": "list", "v": [...]}        {"t": "tuple", "v": [...]}
    {"t": "dict", "v": [[k, v], ...]}
    {"t": "nd", "dtype": "<f8", "shape": [4, 3], "b64": "..."}     (numbers and bools only)
    {"t": "mesh", "state": {...}}                                   (a HalfedgeMesh's arrays)
    {"t": "handle", "kind": "Vertex", "index": 3, "mesh": 0}        (of argument 0)
    {"t": "soup", "faces": {"t": "nd", ...}, "n_vertices": 5}        (a SoupTopology, built again)
    {"t": "float", "v": "nan"}       {"t": "path", "v": "/..."}     {"t": "other", "type": ..., "repr": ...}

Decoding refuses what a message may not hold (object arrays, a nesting deeper than
``MAX_DEPTH``, a message over ``MAX_BYTES``) with :class:`WireError`, which the judge
reports as the learner's function having answered something it cannot read.
"""

from __future__ import annotations

import base64
import json
import math
import socket
import struct
from pathlib import Path, PurePath

import numpy as np

#: The largest message either side reads (a mesh of a few hundred thousand elements fits).
MAX_BYTES = 64 * 1024 * 1024
#: How deeply lists, tuples and dicts may nest in one value.
MAX_DEPTH = 32
#: The numpy element kinds a message may carry: bool, signed, unsigned, float.
_KINDS = "biuf"
_HANDLE_KINDS = ("Vertex", "Halfedge", "Edge", "Face")


class WireError(ValueError):
    """A message that breaks the format (too large, too deep, an unknown shape)."""


# --------------------------------------------------------------------------------------
# Framing: a 4-byte big-endian length, then that many bytes of UTF-8 JSON
# --------------------------------------------------------------------------------------

def send(connection: socket.socket, message: dict) -> None:
    """Send one message (a JSON-able dict)."""
    data = json.dumps(message, separators=(",", ":"), allow_nan=False).encode("utf-8")
    if len(data) > MAX_BYTES:
        raise WireError(f"a message of {len(data):,} bytes is over the limit of {MAX_BYTES:,}")
    connection.sendall(struct.pack(">I", len(data)) + data)


def receive(connection: socket.socket) -> dict:
    """Read one message; ``EOFError`` when the other side closed the connection."""
    (length,) = struct.unpack(">I", _exactly(connection, 4))
    if length > MAX_BYTES:
        raise WireError(f"a message of {length:,} bytes is over the limit of {MAX_BYTES:,}")
    try:
        message = json.loads(_exactly(connection, length).decode("utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError) as error:
        raise WireError(f"a message is not UTF-8 JSON: {error}") from None
    if not isinstance(message, dict):
        raise WireError("a message is not a JSON object")
    return message


def _exactly(connection: socket.socket, count: int) -> bytes:
    parts, missing = [], count
    while missing:
        part = connection.recv(min(missing, 1 << 20))
        if not part:
            raise EOFError("the other side closed the connection")
        parts.append(part)
        missing -= len(part)
    return b"".join(parts)


# --------------------------------------------------------------------------------------
# Values
# --------------------------------------------------------------------------------------

def mesh_state(mesh) -> dict:
    """A HalfedgeMesh's own fields as plain data: its arrays and counters (no caches)."""
    state = {}
    for name, value in vars(mesh).items():
        if isinstance(value, np.ndarray):
            state[name] = _array(value)
        elif isinstance(value, (bool, int, np.integer)) and not isinstance(value, bool):
            state[name] = int(value)
    return state


def encode(value, meshes: list | None = None, depth: int = 0):
    """``value`` as JSON-able data; handles and meshes that are among ``meshes`` by position."""
    meshes = meshes or []
    if depth > MAX_DEPTH:
        raise WireError(f"a value nests deeper than {MAX_DEPTH} levels")
    if value is None or isinstance(value, (bool, str)):
        return value
    if isinstance(value, int):
        return value
    if isinstance(value, float):
        return value if math.isfinite(value) else {"t": "float", "v": repr(value)}
    if isinstance(value, np.generic) and value.dtype.kind in _KINDS:
        return encode(value.item(), meshes, depth)
    if isinstance(value, np.ndarray):
        if value.dtype.kind not in _KINDS:
            return _other(value)
        return _array(value)
    if isinstance(value, (list, tuple)):
        kind = "list" if isinstance(value, list) else "tuple"
        return {"t": kind, "v": [encode(item, meshes, depth + 1) for item in value]}
    if isinstance(value, dict):
        return {"t": "dict", "v": [[encode(k, meshes, depth + 1), encode(v, meshes, depth + 1)]
                                   for k, v in value.items()]}
    if isinstance(value, PurePath):
        return {"t": "path", "v": str(value)}
    kind = type(value).__name__
    if kind in _HANDLE_KINDS and hasattr(value, "index") and hasattr(value, "mesh"):
        owner = next((i for i, mesh in enumerate(meshes) if mesh is value.mesh), -1)
        return {"t": "handle", "kind": kind, "index": int(value.index), "mesh": owner}
    if kind == "SoupTopology" and hasattr(value, "faces") and hasattr(value, "n_vertices"):
        # Rebuilt from what it was built from: its faces and vertex count, never its inner state.
        return {"t": "soup", "faces": _array(np.asarray(value.faces)), "n_vertices": int(value.n_vertices)}
    if kind == "HalfedgeMesh":
        owner = next((i for i, mesh in enumerate(meshes) if mesh is value), -1)
        return {"t": "mesh", "arg": owner, "state": None if owner >= 0 else mesh_state(value)}
    return _other(value)


def _array(array: np.ndarray) -> dict:
    array = np.ascontiguousarray(array)
    return {"t": "nd", "dtype": array.dtype.str, "shape": list(array.shape),
            "b64": base64.b64encode(array.tobytes()).decode("ascii")}


def _other(value) -> dict:
    try:
        text = repr(value)
    except Exception:  # a learner's __repr__ may itself fail
        text = "<no repr>"
    return {"t": "other", "type": type(value).__name__[:80], "repr": text[:200]}


class Opaque:
    """Something the learner's function answered that the wire does not carry (its type and repr)."""

    def __init__(self, type_name: str, text: str):
        self.type_name, self.text = type_name, text

    def __repr__(self) -> str:
        return self.text


def decode(data, meshes: list | None = None, mesh_factory=None, depth: int = 0):
    """The value ``data`` encodes. ``meshes`` are the judge's own meshes that handles refer to;
    ``mesh_factory(state)`` makes a new mesh for a mesh that was not an argument."""
    meshes = meshes or []
    if depth > MAX_DEPTH:
        raise WireError(f"a value nests deeper than {MAX_DEPTH} levels")
    if data is None or isinstance(data, (bool, int, float, str)):
        return data
    if isinstance(data, list):
        raise WireError("a bare list (lists are tagged)")
    if not isinstance(data, dict):
        raise WireError(f"an unknown value of type {type(data).__name__}")
    tag = data.get("t")
    if tag in ("list", "tuple"):
        items = [decode(item, meshes, mesh_factory, depth + 1) for item in _field(data, "v", list)]
        return items if tag == "list" else tuple(items)
    if tag == "dict":
        result = {}
        for pair in _field(data, "v", list):
            if not isinstance(pair, list) or len(pair) != 2:
                raise WireError("a dict entry that is not a [key, value] pair")
            key = decode(pair[0], meshes, mesh_factory, depth + 1)
            try:
                result[key] = decode(pair[1], meshes, mesh_factory, depth + 1)
            except TypeError:
                raise WireError("a dict key that cannot be a key") from None
        return result
    if tag == "nd":
        return array_of(data)
    if tag == "float":
        text = _field(data, "v", str)
        if text not in ("nan", "inf", "-inf"):
            raise WireError(f"an unknown float {text!r}")
        return float(text)
    if tag == "path":
        return Path(_field(data, "v", str))
    if tag == "handle":
        return _handle(data, meshes)
    if tag == "mesh":
        owner = _field(data, "arg", int)
        if 0 <= owner < len(meshes):
            return meshes[owner]
        if mesh_factory is None:
            raise WireError("a mesh where none can be made")
        return mesh_factory(_field(data, "state", dict))
    if tag == "soup":
        from halfedge_edu.core.soup import SoupTopology

        try:
            return SoupTopology(array_of(_field(data, "faces", dict)), _field(data, "n_vertices", int))
        except ValueError as error:
            raise WireError(f"a soup that cannot be built: {error}") from None
    if tag == "other":
        return Opaque(str(data.get("type", "?"))[:80], str(data.get("repr", ""))[:200])
    raise WireError(f"an unknown tag {tag!r}")


def _field(data: dict, name: str, kind: type):
    value = data.get(name)
    if not isinstance(value, kind) or isinstance(value, bool) and kind is int:
        raise WireError(f"field {name!r} is not a {kind.__name__}")
    return value


def array_of(data: dict) -> np.ndarray:
    """The numpy array an ``{"t": "nd"}`` value holds (numbers and bools only)."""
    try:
        dtype = np.dtype(_field(data, "dtype", str))
    except TypeError:
        raise WireError("an array of an unknown dtype") from None
    if dtype.kind not in _KINDS or dtype.itemsize > 8:
        raise WireError(f"an array of dtype {dtype} (only numbers and bools cross)")
    shape = _field(data, "shape", list)
    if len(shape) > 8 or not all(isinstance(n, int) and not isinstance(n, bool) and 0 <= n < MAX_BYTES
                                 for n in shape):
        raise WireError(f"an array of shape {shape!r}")
    raw = base64.b64decode(_field(data, "b64", str), validate=True)
    if len(raw) != dtype.itemsize * int(np.prod(shape, dtype=np.int64)):
        raise WireError("an array whose bytes do not fill its shape")
    return np.frombuffer(raw, dtype=dtype).reshape(shape).copy()


def _handle(data: dict, meshes: list):
    kind, index, owner = _field(data, "kind", str), _field(data, "index", int), _field(data, "mesh", int)
    if kind not in _HANDLE_KINDS:
        raise WireError(f"an unknown handle kind {kind!r}")
    if not 0 <= owner < len(meshes):
        return index  # a handle of a mesh the judge does not have: its number is all that can cross
    mesh = meshes[owner]
    try:
        return getattr(mesh, kind.lower())(index)
    except Exception:  # a deleted or out-of-range element: keep the number, the check says what is wrong
        return index


def apply_mesh_state(mesh, state: dict) -> None:
    """Make ``mesh`` what the learner's function left it: overwrite its arrays and counters.

    Each field must be one the mesh has, of the same kind (an int stays an int, an array
    keeps its element kind and, for positions, its 3 columns), and each array must be
    at least as long as the slots its counter says are in use. WireError otherwise, and
    ``mesh`` is left as it was.
    """
    current = vars(mesh)
    new: dict[str, object] = {}
    for name, old in current.items():
        if isinstance(old, np.ndarray):
            if name not in state or not isinstance(state[name], dict):
                raise WireError(f"the mesh came back without its {name.strip('_')} array")
            array = array_of(state[name])
            if array.dtype.kind != old.dtype.kind or array.ndim != old.ndim or array.shape[1:] != old.shape[1:]:
                raise WireError(f"the mesh's {name.strip('_')} array came back as {array.dtype}{list(array.shape)}, "
                                f"not {old.dtype}[n{', ' + str(old.shape[1]) if old.ndim > 1 else ''}]")
            new[name] = array.astype(old.dtype, copy=False)
        elif isinstance(old, int) and not isinstance(old, bool):
            value = state.get(name)
            if not isinstance(value, int) or isinstance(value, bool) or value < 0:
                raise WireError(f"the mesh's counter {name.strip('_')} came back as {value!r}")
            new[name] = value
    for kind, arrays in (("vertex", ("_positions", "_vertex_halfedge", "_vertex_deleted")),
                         ("edge", ("_edge_deleted",)),
                         ("face", ("_face_halfedge", "_face_deleted"))):
        slots = new.get(f"_n_{kind}_slots", 0)
        deleted = new.get(f"_n_deleted_{'vertices' if kind == 'vertex' else kind + 's'}", 0)
        short = [a for a in arrays if a in new and len(new[a]) < slots]
        if short or deleted > slots:
            raise WireError(f"the mesh came back with {slots} {kind} slots but shorter arrays or more deleted")
    halfedge_slots = 2 * new.get("_n_edge_slots", 0)
    if any(name in new and len(new[name]) < halfedge_slots
           for name in ("_halfedge_next", "_halfedge_prev", "_halfedge_vertex", "_halfedge_face")):
        raise WireError(f"the mesh came back with {halfedge_slots} halfedge slots but shorter arrays")
    current.update(new)
    if hasattr(mesh, "_cache"):
        mesh._cache = {}
    if hasattr(mesh, "topology_changed"):
        mesh.topology_changed()

"""meshgap on Dask: the batch of meshgap.Scene over poses spread on a cluster, and clearance data sets in Zarr.

    import meshgap.distributed as md
    client = md.connect()                        # a local cluster; md.connect("tcp://HOST:8786") for a scheduler
    r = md.distance("maps/hand_bowl/hand_bowl.cfg", poses, chunks=4096)   # a dict of Dask arrays
    d = r["distance"].compute()
    md.label("maps/hand_bowl/hand_bowl.cfg", 10_000_000, out="labels.zarr")

A problem (`source`) is a .cfg path or a (robot, world) pair of mesh paths; a robot problem file (robot.urdf, or
robot.1 ...) takes (N, dof) states in distance() and in_collision(), answered as RobotScene.distance answers them. Its files are checked and hashed on the
client; each worker process builds its Scene once per content hash and keeps it for every chunk it runs (the Scene is
never sent over the network), so the files must be readable at the same paths on every worker. Answers are those of
Scene.distance on the same poses, bit for bit. Needs Debian's python3-dask; connect() needs python3-distributed and
label() python3-zarr.
"""
import contextlib
import hashlib
import math
import os
import re
import shutil
import socket
import threading
import warnings

import numpy as np

try:
    import dask
    import dask.array as da
except ImportError as error:  # pragma: no cover - depends on the machine
    raise ImportError("meshgap.distributed needs Dask (Debian: apt-get install python3-dask python3-distributed "
                      "python3-zarr): %s" % error) from None

from . import _meshgap

# The fields of Scene.distance, in the order they are packed in one float64 row per pose (an int64 obstacle index
# and the booleans are exact in float64), with their dtype and width.
FIELDS = (("distance", np.float64, 1), ("on_a", np.float64, 3), ("on_b", np.float64, 3),
          ("obstacle", np.int64, 1), ("in_collision", np.bool_, 1), ("certified", np.bool_, 1),
          ("open_body", np.bool_, 1))
DEFAULT_CHUNK = 16 * _meshgap.SCENE_BATCH_BLOCK  # rows per task: a multiple of the batch's block


class Problem:
    """A problem named by its files: a .cfg (kind "cfg": files = (cfg, robot, world)), a pair of meshes (kind
    "meshes": files = (robot, world)) or a robot problem file (kind "robot": files = (cfg, the files it names); robot
    = (state numbers, links, self pairs)), with the hash of their contents (key). Small and picklable: this, not the
    Scene, travels to the workers. Build it once with problem(source) to hash the files once."""

    def __init__(self, kind, files, key, planar, volume, robot=None):
        self.kind, self.files, self.key, self.planar, self.volume = kind, tuple(files), key, planar, volume
        self.robot = robot

    def __repr__(self):
        return "<meshgap.distributed.Problem %s %s>" % (self.kind, ", ".join(self.files))

    def __dask_tokenize__(self):
        return (self.kind, self.files, self.key)


def _hash_files(paths):
    digest = hashlib.sha256()
    for path in paths:
        with open(path, "rb") as f:
            for block in iter(lambda: f.read(1 << 20), b""):
                digest.update(block)
        digest.update(b"\0")
    return digest.hexdigest()


def _cut(text, limit=80):
    """text for an error message, cut to its first limit characters (an input may be megabytes long)."""
    return text if len(text) <= limit else text[:limit] + "... (%d characters)" % len(text)


def _shown(value):
    """repr(value) for an error message, cut (_cut())."""
    return _cut(repr(value))


def _missing(path, where):
    return FileNotFoundError("%s: no such file%s" % (_cut(path, 1000), where))


def _read_cfg(path):
    """The [problem] keys of an OMPL.app .cfg (the grammar meshgap's reader takes: key = value, # comments)."""
    keys, section = {}, None
    with open(path, encoding="utf-8", errors="replace") as f:
        for line in f:
            line = line.strip()
            if not line or line[0] in "#;":
                continue
            if line.startswith("["):
                section = line.strip("[]").strip()
            elif section == "problem" and "=" in line:
                key, value = line.split("=", 1)
                keys[key.strip()] = value.strip()
    return keys


def _robot_problem(cfg, keys):
    """The Problem of a robot problem file (robot.urdf, or robot.1 ...): the cfg and the files its keys name are
    hashed (the meshes a URDF names are not: change the URDF or the cfg when they change); the robot is built here
    once to learn its state numbers, links and self pairs (RobotScene.from_cfg's errors name the file and line)."""
    named = [keys[k] for k in ("robot.urdf", "robot.srdf", "world") if k in keys]
    if keys.get("attach", "").split():
        named.append(keys["attach"].split()[0])
    n = 1
    while "robot.%d" % n in keys:
        named.append(keys["robot.%d" % n])
        n += 1
    files = [cfg]
    for name in named:
        path = os.path.normpath(os.path.join(os.path.dirname(cfg), name))
        if not os.path.isfile(path):
            raise FileNotFoundError("%s: '%s' does not exist" % (cfg, _cut(path, 1000)))
        files.append(path)
    robot = _meshgap.RobotScene.from_cfg(cfg)
    shape = (robot.dimension, len(robot.link_names), len(robot.self_pairs))
    return Problem("robot", files, _hash_files(files), None, None, shape)


def problem(source):
    """The Problem of a .cfg path or a (robot, world) pair of mesh paths, its files checked and hashed here.
    FileNotFoundError naming a missing file; ValueError for anything else than those two forms."""
    if isinstance(source, Problem):
        return source
    if isinstance(source, (str, os.PathLike)):
        cfg = os.path.abspath(os.fspath(source))
        if not os.path.isfile(cfg):
            raise _missing(cfg, "")
        keys = _read_cfg(cfg)
        if "robot.urdf" in keys or "robot.1" in keys:
            return _robot_problem(cfg, keys)
        files = [cfg]
        for role in ("robot", "world"):
            if role not in keys:
                raise ValueError("%s: missing required key '%s' in [problem]" % (cfg, role))
            mesh = os.path.join(os.path.dirname(cfg), keys[role])
            if not os.path.isfile(mesh):
                raise FileNotFoundError("%s: %s mesh '%s' does not exist" % (cfg, role, _cut(mesh, 1000)))
            files.append(os.path.normpath(mesh))
        planar = "start.z" not in keys
        axes = "xy" if planar else "xyz"
        volume = None
        if all("volume.%s.%s" % (end, a) in keys for end in ("min", "max") for a in axes):
            volume = tuple(tuple(float(keys["volume.%s.%s" % (end, a)]) for a in axes) for end in ("min", "max"))
        return Problem("cfg", files, _hash_files(files), planar, volume)
    if isinstance(source, (tuple, list)) and len(source) == 2 and all(
            isinstance(p, (str, os.PathLike)) for p in source):
        files = [os.path.abspath(os.fspath(p)) for p in source]
        for path in files:
            if not os.path.isfile(path):
                raise _missing(path, "")
        return Problem("meshes", files, _hash_files(files), None, None)
    raise ValueError("source: expected a .cfg path or a (robot, world) pair of mesh paths, got %s" % _shown(source))


# The worker side: one Scene per problem's content hash in each process, built on first use.
_scenes = {}
_builds = {}
_lock = threading.Lock()


def _where():
    return " on worker %s (pid %d)" % (socket.gethostname(), os.getpid())


def scene(source):
    """This process's Scene of a problem, built once per content hash and kept (what each task calls)."""
    p = problem(source) if not isinstance(source, Problem) else source
    with _lock:
        built = _scenes.get(p.key)
        if built is not None:
            return built
        for path in p.files:
            if not os.path.isfile(path):
                raise _missing(path, _where())
        if _hash_files(p.files) != p.key:
            raise ValueError("%s: the files%s differ from those the client hashed" % (", ".join(p.files), _where()))
        if p.kind == "robot":
            built = _meshgap.RobotScene.from_cfg(p.files[0])
        else:
            built = _meshgap.Scene.from_cfg(p.files[0]) if p.kind == "cfg" else _meshgap.Scene(*p.files)
        _scenes[p.key] = built
        _builds[p.key] = _builds.get(p.key, 0) + 1
        return built


def scene_builds():
    """How many Scenes this process built, per problem key (read on the workers with client.run(scene_builds))."""
    with _lock:
        return dict(_builds)


def _fields(p):
    """The fields of the problem's distance answer: (name, dtype, width, a column per pose (width 1) or a row)."""
    if p.kind != "robot":
        return tuple((name, dtype, width, width > 1) for name, dtype, width in FIELDS)
    _, links, pairs = p.robot
    return (("distance", np.float64, 1, False), ("in_collision", np.bool_, 1, False),
            ("certified", np.bool_, 1, False), ("self_pair", np.bool_, 1, False), ("link", np.int64, 1, False),
            ("obstacle", np.int64, 1, False), ("other_link", np.int64, 1, False), ("on_a", np.float64, 3, True),
            ("on_b", np.float64, 3, True), ("link_clearance", np.float64, links, True),
            ("link_obstacle_distance", np.float64, links, True), ("self_pair_distance", np.float64, pairs, True))


_ROW = re.compile(r"^(poses|states)\[(\d+)\]")


@contextlib.contextmanager
def _global_rows(block_info):
    """A ValueError of Scene or RobotScene naming a row of the block (poses[i], states[i]) names its row of the
    whole array instead (the block's first row added)."""
    try:
        yield
    except ValueError as error:
        first = block_info[0]["array-location"][0][0] if block_info and 0 in block_info else 0
        message = str(error)
        found = _ROW.match(message)
        if not found or not first:
            raise
        raise ValueError("%s[%d]%s" % (found.group(1), int(found.group(2)) + first, message[found.end():])) from None


def _distance_block(block, p, exact, warm, depth, block_info=None):
    block = np.ascontiguousarray(block, dtype=np.float64)
    with _global_rows(block_info):
        if p.kind == "robot":
            r = scene(p).distance(block)
        else:
            r = scene(p).distance(block, exact=exact, warm=warm, depth=depth)
    fields = _fields(p)
    packed = np.empty((len(block), sum(width for _, _, width, _ in fields)))
    column = 0
    for name, _, width, _ in fields:
        packed[:, column:column + width] = r[name].reshape(len(block), width)
        column += width
    return packed


def _collision_block(block, p, block_info=None):
    with _global_rows(block_info):
        return scene(p).in_collision(np.ascontiguousarray(block, dtype=np.float64))


def _pose_array(poses, p, chunks):
    """A Dask array of float64 poses, rows chunked, all columns in one chunk; ValueError for a wrong shape."""
    if not isinstance(poses, da.Array):
        poses = np.asarray(poses)
    shape = tuple(poses.shape)
    if p.kind == "robot":
        if len(shape) != 2 or shape[1] != p.robot[0]:
            raise ValueError("states: expected an array of shape (N, %d) (the robot's state numbers, as "
                             "RobotScene.state_names), got shape %s" % (p.robot[0], shape))
        columns = (p.robot[0],)
    else:
        columns = (3,) if p.planar else (7,) if p.planar is False else (3, 7)
    if len(shape) != 2 or shape[1] not in columns:
        raise ValueError("poses: expected an array of shape (N, %s) (%s), got shape %s" % (
            " or ".join(map(str, columns)),
            "x y theta" if columns == (3,) else "x y z qx qy qz qw" if columns == (7,) else
            "x y z qx qy qz qw, or x y theta", shape))
    if chunks is not None and (isinstance(chunks, bool) or not isinstance(chunks, (int, np.integer)) or chunks <= 0):
        raise ValueError("chunks: expected a positive integer (rows per task) or None, got %s" % _shown(chunks))
    rows = chunks if chunks is not None else (poses.chunks[0] if isinstance(poses, da.Array) else DEFAULT_CHUNK)
    if isinstance(poses, da.Array):
        return poses.astype(np.float64).rechunk((rows, -1))
    return da.from_array(poses.astype(np.float64, copy=False), chunks=(rows, -1))


def distance(source, poses, chunks=None, exact=True, warm=True, depth=True):
    """Scene.distance over a Dask array (or a numpy array, wrapped) of poses, (N, 7) x y z qx qy qz qw or (N, 3) x y
    theta, rows chunked (chunks: rows per task; default the array's own chunks, or DEFAULT_CHUNK). Returns a dict of
    Dask arrays with Scene.distance's fields, all from one task per chunk (compute them together:
    dask.compute(r)). Each task runs Scene.distance(block, exact=, warm=, depth=) with one thread: the warm start is
    carried within a chunk, the answers identical to one Scene.distance over all the poses.

    A robot problem file (robot.urdf, or robot.1 ...) takes (N, dof) states instead and gives RobotScene.distance's
    fields (every pair answered: link_clearance, link_obstacle_distance, self_pair_distance too); it is always
    exact, with the depth, so exact and depth must stay True."""
    p = problem(source)
    if p.kind == "robot" and not (exact and depth):
        raise ValueError("a robot problem is answered exactly, with the depth: exact and depth must be True")
    x = _pose_array(poses, p, chunks)
    fields = _fields(p)
    width = sum(w for _, _, w, _ in fields)
    # meta given: Dask would otherwise call the function on an empty block here, building the Scene on the client.
    packed = x.map_blocks(_distance_block, p, exact, warm, depth, dtype=np.float64, meta=np.empty((0, width)),
                          chunks=(x.chunks[0], (width,)), name="meshgap-distance")
    out, column = {}, 0
    for name, dtype, w, row in fields:
        part = packed[:, column:column + w] if row else packed[:, column]
        out[name] = part.astype(dtype)
        column += w
    return out


def in_collision(source, poses, chunks=None):
    """Scene.in_collision (RobotScene.in_collision for a robot problem file) over a Dask array of poses (states), as
    distance(): a Dask bool array (N,)."""
    p = problem(source)
    x = _pose_array(poses, p, chunks)
    return x.map_blocks(_collision_block, p, dtype=np.bool_, meta=np.empty((0,), dtype=np.bool_), drop_axis=1,
                        name="meshgap-in-collision")


def connect(address=None, timeout=10, **kwargs):
    """A distributed.Client: of a new local cluster (address None, keywords to distributed.Client, e.g.
    n_workers=), or of the scheduler at address ("tcp://HOST:8786"). ConnectionError naming the address when the
    scheduler is not reached within timeout seconds."""
    try:
        import distributed
    except ImportError as error:
        raise ImportError("meshgap.distributed.connect needs Debian's python3-distributed: %s" % error) from None
    if address is None:
        return distributed.Client(**kwargs)
    try:
        return distributed.Client(address, timeout=timeout, **kwargs)
    except (OSError, TimeoutError) as error:
        raise ConnectionError("cannot reach the Dask scheduler at %s within %g s: %s" % (address, timeout, error)) \
            from None


SAMPLERS = ("uniform", "near", "path")
NEAR_STEPS = 24  # bisection steps of the "near" sampler: its pairs end 2^-24 of their first length apart
PATH_STATES = 32  # poses per straight path of the "path" sampler
_NEAR_ROUNDS = 64


def _uniform(rng, volume, planar, count):
    lo, hi = np.asarray(volume[0], dtype=np.float64), np.asarray(volume[1], dtype=np.float64)
    position = lo + (hi - lo) * rng.random((count, len(lo)))
    if planar:
        return np.column_stack([position[:, :2], rng.uniform(-math.pi, math.pi, count)])
    u = rng.random((count, 3))
    a, b = np.sqrt(1.0 - u[:, 0]), np.sqrt(u[:, 0])
    q = np.column_stack([a * np.sin(2 * math.pi * u[:, 1]), a * np.cos(2 * math.pi * u[:, 1]),
                         b * np.sin(2 * math.pi * u[:, 2]), b * np.cos(2 * math.pi * u[:, 2])])
    return np.column_stack([position, q])


def uniform_poses(volume, planar, count, seed, index):
    """count poses uniform in volume ((min...), (max...)): position uniform, rotation uniform in SO(3) (a uniform
    unit quaternion, x y z w) or theta uniform in [-pi, pi) when planar; drawn from the generator seeded with
    (seed, index), so chunk index of a data set is the same on any machine."""
    return _uniform(np.random.default_rng([seed, index]), volume, planar, count)


def interpolate(a, b, t, planar):
    """Poses between rows of a and b at fractions t (one per row): position linear, theta along the shorter arc
    (wrapped to [-pi, pi)) when planar, else the quaternion by slerp along the shorter arc (x y z w, unit)."""
    t = np.asarray(t, dtype=np.float64).reshape(-1, 1)
    axes = 2 if planar else 3
    out = np.empty(a.shape)
    out[:, :axes] = a[:, :axes] + t * (b[:, :axes] - a[:, :axes])
    if planar:
        turn = np.remainder(b[:, 2] - a[:, 2] + math.pi, 2 * math.pi) - math.pi
        out[:, 2] = np.remainder(a[:, 2] + t[:, 0] * turn + math.pi, 2 * math.pi) - math.pi
        return out
    qa, qb = a[:, 3:], b[:, 3:] * np.where(np.sum(a[:, 3:] * b[:, 3:], axis=1) < 0, -1.0, 1.0)[:, None]
    cos = np.clip(np.sum(qa * qb, axis=1), -1.0, 1.0)
    angle = np.arccos(cos)[:, None]
    sin = np.sin(angle)
    small = sin[:, 0] < 1e-9
    wa = np.where(small[:, None], 1.0 - t, np.sin((1.0 - t) * angle) / np.where(small[:, None], 1.0, sin))
    wb = np.where(small[:, None], t, np.sin(t * angle) / np.where(small[:, None], 1.0, sin))
    q = wa * qa + wb * qb
    out[:, 3:] = q / np.linalg.norm(q, axis=1, keepdims=True)
    return out


def near_poses(scene, volume, planar, count, seed, index, steps=NEAR_STEPS):
    """count poses near the obstacles, in pairs straddling contact: uniform poses of volume are split into free and
    colliding ones (scene.in_collision), a free pose is paired with a colliding one, and the segment between them
    (interpolate()) is bisected steps times, keeping a free and a colliding end; rows 0, 2, 4... are the free ends,
    rows 1, 3, 5... the colliding ones, 2^-steps of the pair's first segment apart. Seeded with (seed, index, 1);
    ValueError when no pose of the volume collides (or none is free) in 64 rounds of draws."""
    rng = np.random.default_rng([seed, index, 1])
    pairs = (count + 1) // 2
    free, hit, drawn = [], [], 0
    for _ in range(_NEAR_ROUNDS):
        x = _uniform(rng, volume, planar, max(2 * pairs, 64))
        colliding = np.asarray(scene.in_collision(x), dtype=bool)
        drawn += len(x)
        free.append(x[~colliding])
        hit.append(x[colliding])
        if min(sum(map(len, free)), sum(map(len, hit))) >= pairs:
            break
    free, hit = np.concatenate(free), np.concatenate(hit)
    if min(len(free), len(hit)) < pairs:
        raise ValueError("sampler 'near': %d of %d uniform poses of the volume %r collide: no contact to sample "
                         "near" % (len(hit), drawn, volume))
    a, b = free[:pairs].copy(), hit[:pairs].copy()
    for _ in range(steps):
        middle = interpolate(a, b, np.full(pairs, 0.5), planar)
        colliding = np.asarray(scene.in_collision(middle), dtype=bool)
        a[~colliding] = middle[~colliding]
        b[colliding] = middle[colliding]
    out = np.empty((2 * pairs, a.shape[1]))
    out[0::2], out[1::2] = a, b
    return out[:count]


def path_poses(volume, planar, count, seed, index, states=PATH_STATES):
    """count poses along straight paths: pairs of poses uniform in volume, each joined by states poses evenly spaced
    from one to the other (interpolate(), both ends included), path after path. Seeded with (seed, index, 2)."""
    rng = np.random.default_rng([seed, index, 2])
    paths = -(-count // states)
    ends = _uniform(rng, volume, planar, 2 * paths)
    t = np.tile(np.linspace(0.0, 1.0, states), paths)
    poses = interpolate(np.repeat(ends[:paths], states, axis=0), np.repeat(ends[paths:], states, axis=0), t, planar)
    return poses[:count]


def _draw(p, params, count, index):
    """The poses of chunk index of a data set, by its sampler."""
    volume, planar, seed = params["volume"], params["planar"], params["seed"]
    if params["sampler"] == "near":
        return near_poses(scene(p), volume, planar, count, seed, index, params["steps"])
    if params["sampler"] == "path":
        return path_poses(volume, planar, count, seed, index, params["states"])
    return uniform_poses(volume, planar, count, seed, index)


def _label_chunk(p, out, index, params):
    import zarr
    n, chunk = params["n"], params["chunk"]
    start, stop = index * chunk, min(n, (index + 1) * chunk)
    poses = _draw(p, params, stop - start, index)
    r = scene(p).distance(poses, exact=True, depth=True)
    try:
        group = zarr.open_group(out, mode="r+")
    except Exception as error:  # not on this worker's file system
        raise FileNotFoundError("%s: the Zarr store is not readable%s (label() needs a folder every worker shares): "
                                "%s" % (out, _where(), error)) from None
    try:
        group["poses"][start:stop] = poses
        for name, _, _ in FIELDS:
            group[name][start:stop] = r[name]
        group["done"][index] = 1  # after the data: a chunk marked done is complete
    except (OSError, KeyError) as error:  # Zarr's folder store: KeyError for a chunk file it could not write
        raise _unwritable(error, "%s: cannot write the data set's rows %d to %d%s: %s" % (
            out, start, stop, _where(), error.strerror if isinstance(error, OSError) else error)) from None
    return index


def _store(out, params, p):
    """Open the data set at out, or create it (in a temporary folder renamed into place: never half made)."""
    import zarr
    if os.path.exists(out):
        try:
            group = zarr.open_group(out, mode="r+")
            made = dict(group.attrs)
        except Exception as error:
            raise ValueError("%s: exists and is not a meshgap data set (%s)" % (out, error)) from None
        if made.get("params") != params:
            raise ValueError("%s: a data set of other parameters %s (this run: %s); choose another out" % (
                out, made.get("params"), params))
        missing = [name for name, _, _ in FIELDS if name not in group]
        if missing:  # an older meshgap's, whose witness points were on_robot and on_obstacle
            raise ValueError("%s: a data set without the fields %s (made by an older meshgap); choose another out" % (
                out, ", ".join(missing)))
        return group
    temporary = "%s.tmp-%d" % (out, os.getpid())
    shutil.rmtree(temporary, ignore_errors=True)
    try:
        # Made here first: Zarr's folder store reports a folder it cannot write as a KeyError of its first key.
        os.makedirs(temporary)
        group = zarr.open_group(temporary, mode="w")
        n, chunk, d = params["n"], params["chunk"], 3 if params["planar"] else 7
        group.zeros("poses", shape=(n, d), chunks=(chunk, d), dtype=np.float64)
        for name, dtype, width in FIELDS:
            group.zeros(name, shape=(n,) if width == 1 else (n, width),
                        chunks=(chunk,) if width == 1 else (chunk, width), dtype=dtype)
        group.zeros("done", shape=(-(-n // chunk),), chunks=(1,), dtype=np.uint8)
        group.attrs["params"] = params
        group.attrs["files"] = list(p.files)
        os.rename(temporary, out)
    except (OSError, KeyError) as error:
        shutil.rmtree(temporary, ignore_errors=True)
        reason = error.strerror if isinstance(error, OSError) and error.strerror else "cannot write %s" % error
        raise _unwritable(error, "%s: cannot create the data set in %s: %s" % (out, os.path.dirname(out), reason)) \
            from None
    return zarr.open_group(out, mode="r+")


def _unwritable(error, message):
    """The OSError to raise for a data set that cannot be written: of error's class when it is one (PermissionError,
    NotADirectoryError, ...), else PermissionError (Zarr's KeyError for a file it could not write)."""
    return type(error)(message) if isinstance(error, OSError) else PermissionError(message)


def _around(p):
    """The volume of a problem without one: the world's bounding box grown by the robot's reach from its origin."""
    if p.kind == "cfg":
        raise ValueError("volume: %s gives none (volume.min.* and volume.max.*); pass volume=((min...), (max...))"
                         % p.files[0])
    robot, world = (_meshgap.load_mesh(path)[0] for path in p.files)
    reach = float(np.linalg.norm(robot, axis=1).max()) if len(robot) else 0.0
    return world.min(axis=0) - reach, world.max(axis=0) + reach


def _current_client(client):
    if client is False:
        return None
    if client is not None:
        return client
    try:
        from distributed import get_client
        return get_client()
    except (ImportError, ValueError):
        return None


def _compute(tasks, client, progress):
    """Run label()'s tasks on client with its progress bar, or on local threads (client None)."""
    if tasks and client is not None:
        futures = client.compute(tasks)
        if progress:
            from distributed import progress as show
            show(futures)
        client.gather(futures)
    elif tasks:
        from dask.diagnostics import ProgressBar
        with warnings.catch_warnings():  # client=False beside an active client: local threads, as asked
            warnings.filterwarnings("ignore", "Running on a single-machine scheduler")
            with ProgressBar() if progress else contextlib.nullcontext():
                dask.compute(*tasks, scheduler="threads")


def label(source, n, out="labels.zarr", sampler="uniform", chunk=DEFAULT_CHUNK, seed=0, volume=None, client=None,
          progress=True):
    """Draw n poses in volume (default the cfg's volume, or for a pair of meshes the world's bounding box grown by
    the robot's reach) with sampler "uniform" (uniform_poses()), "near" (pairs straddling contact, near_poses()) or
    "path" (along straight paths between uniform poses, path_poses()), seeded per chunk, and write them with their exact clearance and witness points (Scene.distance's fields, exact=True, depth=True)
    to the Zarr group out, one task per chunk of rows, each writing its rows then its mark in done. A rerun with the
    same arguments computes only the chunks not marked done, so a killed run resumes. Runs on the current
    distributed Client (or client), with its progress bar; else (or with client=False) on local threads with Dask's
    ProgressBar. Returns
    {"out", "chunks", "computed"} (computed: the chunks this run wrote)."""
    import zarr  # fail here, not on the workers, when it is missing
    p = problem(source)
    if p.kind == "robot":
        raise ValueError("label: %s is a robot problem; label() draws poses of one rigid robot (distance() takes a "
                         "robot's (N, dof) states)" % p.files[0])
    if sampler not in SAMPLERS:
        raise ValueError("sampler: %s is not known (%s)" % (_shown(sampler), ", ".join(SAMPLERS)))
    if not (isinstance(n, (int, np.integer)) and n > 0) or not (isinstance(chunk, (int, np.integer)) and chunk > 0):
        raise ValueError("n and chunk: expected positive integers, got n=%s, chunk=%s" % (_shown(n), _shown(chunk)))
    volume = volume if volume is not None else p.volume if p.volume is not None else _around(p)
    planar = bool(p.planar)
    volume = [[float(v) for v in volume[0]], [float(v) for v in volume[1]]]
    if len(volume[0]) != (2 if planar else 3) or len(volume[1]) != len(volume[0]) or any(
            lo >= hi for lo, hi in zip(*volume)):
        raise ValueError("volume: expected ((min...), (max...)) of %d axes, max above min, got %s" % (
            2 if planar else 3, _shown(volume)))
    out = os.path.abspath(os.fspath(out))
    params = {"n": int(n), "chunk": int(chunk), "seed": int(seed), "sampler": sampler, "planar": planar,
              "volume": volume, "problem": p.key}
    if sampler == "near":
        params["steps"] = NEAR_STEPS
    elif sampler == "path":
        params["states"] = PATH_STATES
    created = not os.path.exists(out)
    group = _store(out, params, p)
    done = group["done"][:]
    todo = [int(i) for i in np.flatnonzero(done == 0)]
    tasks = [dask.delayed(_label_chunk, pure=False)(p, out, i, params) for i in todo]
    client = _current_client(client)
    try:
        _compute(tasks, client, progress)
    except BaseException:
        if created and not zarr.open_group(out, mode="r")["done"][:].any():
            shutil.rmtree(out, ignore_errors=True)  # made by this call, no chunk done: nothing left half made
        raise
    # A worker killed while writing leaves its chunk's temporary file (NAME.UUID.partial, renamed into place once
    # written): the chunk was rerun, the leftover goes.
    for folder, _, names in os.walk(out):
        for name in names:
            if name.endswith(".partial"):
                os.remove(os.path.join(folder, name))
    return {"out": out, "chunks": len(done), "computed": len(todo)}

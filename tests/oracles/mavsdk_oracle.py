"""QGroundControl `.plan` files checked with the real MAVSDK library, over real MAVLink.

For every `*.plan` under the folders given, a MAVSDK ground station imports the file with
`MissionRaw.import_qgroundcontrol_mission` and uploads its mission items (and, when the file
has them, its geofence and rally points) over MAVLink to a MAVSDK autopilot (the
`MissionRawServer` plugin) running in a child process. Both ends talk UDP on 127.0.0.1 only.
What the import produced and what the autopilot received are both compared, field by field,
against the .plan as read here with the json module: item count and seq, command, frame,
params 1-4 (null is NaN), x/y (degrees x 1e7, rounded half away from zero), z and
autocontinue. MAVLink carries params and z as 32-bit floats, so the file's value rounded to
float32 is what must arrive, bit for bit. Between the import and the autopilot every field
(current, mission_type too) must be identical.

Needs the native MAVSDK binding (`pip install "mavsdk>=4.1,<5"`; 4.x calls libmavsdk
directly, so there is no mavsdk_server process and no gRPC).

Run: python tests/oracles/mavsdk_oracle.py DIR [DIR ...]
     python tests/oracles/mavsdk_oracle.py --self-test [DIR ...]
The self-test shows that a difference between the file and what MAVSDK imports or uploads is
caught (an altered copy fed only to the import, an item tampered with between import and
upload, a dropped item, a 6-param item, corrupt JSON). Exit status 1 when anything failed or
MAVSDK could not run; the last line is always `mavsdk: N passed, M failed`.
"""
import argparse
import asyncio
import copy
import glob
import json
import math
import os
import shutil
import socket
import struct
import subprocess
import sys
import tempfile
import threading
import time

FILE_TIMEOUT = 30.0  # one .plan, import to last upload
STEP_TIMEOUT = 10.0  # one MAVSDK call or one event from the autopilot
START_TIMEOUT = 20.0  # the autopilot process up, and seen by the ground station
MARK = "@@mavsdk-oracle "  # prefix of the autopilot child's protocol lines on its stdout
FIELDS = ("seq", "frame", "command", "current", "autocontinue", "param1", "param2",
          "param3", "param4", "x", "y", "z", "mission_type")
MISSION, FENCE, RALLY = 0, 1, 2  # MAV_MISSION_TYPE
MAV_FRAME_GLOBAL, MAV_FRAME_MISSION, MAV_FRAME_GLOBAL_RELATIVE_ALT = 0, 2, 3
SERVER_SUCCESS = 1  # MissionRawServerResult.SUCCESS


# ---------------------------------------------------------------- what the file says

def f32(value):
    """The value as MAVLink's float fields carry it (null is NaN, as MAVSDK imports it)."""
    if value is None:
        return math.nan
    try:
        return struct.unpack("<f", struct.pack("<f", float(value)))[0]
    except OverflowError:
        return math.copysign(math.inf, float(value))


def coordinate(value, frame):
    """x/y of MISSION_ITEM_INT: degrees x 1e7 rounded half away from zero (MAVSDK's
    std::round); in MAV_FRAME_MISSION the raw param, truncated to an integer."""
    if value is None:
        return 0
    if frame == MAV_FRAME_MISSION:
        return int(f32(value))
    scaled = float(value) * 1e7
    return int(math.copysign(math.floor(abs(scaled) + 0.5), scaled))


def is_number(value):
    return value is None or (isinstance(value, (int, float)) and not isinstance(value, bool))


def expected_items(doc, home_first):
    """(mission, fence, rally, problems): the items the file asks for, as MAVLink items.

    Each item is a dict of FIELDS (less `current`, which the file does not give) and `where`,
    which names it in messages. `problems` lists what in the file MAVLink cannot carry."""
    problems = []
    if not isinstance(doc, dict):
        return [], [], [], ["top level is not a JSON object"]
    if doc.get("fileType") != "Plan":
        problems.append(f"fileType is {doc.get('fileType')!r}, not 'Plan'")
    mission = doc.get("mission")
    if not isinstance(mission, dict) or not isinstance(mission.get("items"), list):
        return [], [], [], problems + ["no mission.items list"]

    items = []
    if home_first:  # what MAVSDK inserts for ArduPilot: plannedHomePosition as item 0
        home = mission.get("plannedHomePosition") or [None, None, None]
        items.append(dict(where="home (plannedHomePosition)", frame=MAV_FRAME_GLOBAL,
                          command=16, autocontinue=1, param1=0.0, param2=0.0, param3=0.0,
                          param4=0.0, x=coordinate(home[0], 0), y=coordinate(home[1], 0),
                          z=f32(home[2]), mission_type=MISSION))
    for index, raw in enumerate(mission["items"]):
        where = f"item {index + 1}"
        if isinstance(raw, dict) and raw.get("doJumpId") is not None:
            where += f" (doJumpId {raw.get('doJumpId')})"
        if not isinstance(raw, dict) or raw.get("type") != "SimpleItem":
            problems.append(f"{where}: not a SimpleItem")
            continue
        params = raw.get("params")
        command, frame, auto = raw.get("command"), raw.get("frame"), raw.get("autoContinue")
        if not isinstance(params, list) or len(params) != 7:
            count = len(params) if isinstance(params, list) else "no"
            problems.append(f"{where}: {count} params, a MAVLink item has 7")
            continue
        if not all(is_number(p) for p in params):
            problems.append(f"{where}: a param is neither a number nor null: {params}")
            continue
        if not isinstance(command, int) or isinstance(command, bool) or not 0 <= command <= 65535:
            problems.append(f"{where}: command {command!r} is not a uint16")
            continue
        if not isinstance(frame, int) or isinstance(frame, bool) or not 0 <= frame <= 255:
            problems.append(f"{where}: frame {frame!r} is not a uint8")
            continue
        if not isinstance(auto, bool):
            problems.append(f"{where}: autoContinue {auto!r} is not true/false")
            continue
        if frame == MAV_FRAME_MISSION and any(
                p is not None and float(p) != int(float(p)) for p in params[4:6]):
            problems.append(f"{where}: frame 2 carries params 5/6 as integers, file has "
                            f"{params[4]}, {params[5]}")
        x, y = coordinate(params[4], frame), coordinate(params[5], frame)
        if not (-2**31 <= x < 2**31 and -2**31 <= y < 2**31):
            problems.append(f"{where}: params 5/6 {params[4]}, {params[5]} overflow int32")
            continue
        items.append(dict(where=where, frame=frame, command=command, autocontinue=int(auto),
                          param1=f32(params[0]), param2=f32(params[1]),
                          param3=f32(params[2]), param4=f32(params[3]), x=x, y=y,
                          z=f32(params[6]), mission_type=MISSION))
    if not items:
        problems.append("no mission items")

    fence = []
    geofence = doc.get("geoFence") or {}
    for number, polygon in enumerate(geofence.get("polygons") or [], 1):
        vertices = polygon.get("polygon") or []
        inclusion = polygon.get("inclusion", True)
        if len(vertices) < 3:
            problems.append(f"geofence polygon {number}: {len(vertices)} vertices, needs 3")
        for vertex, point in enumerate(vertices, 1):
            fence.append(dict(where=f"fence polygon {number} vertex {vertex}",
                              command=5001 if inclusion else 5002, param1=f32(len(vertices)),
                              x=coordinate(point[0], 0), y=coordinate(point[1], 0),
                              mission_type=FENCE))
    for number, circle in enumerate(geofence.get("circles") or [], 1):
        center = (circle.get("circle") or {}).get("center") or [None, None]
        fence.append(dict(where=f"fence circle {number}",
                          command=5003 if circle.get("inclusion") else 5004,
                          param1=f32((circle.get("circle") or {}).get("radius")),
                          x=coordinate(center[0], 0), y=coordinate(center[1], 0),
                          mission_type=FENCE))
    rally = []
    for number, point in enumerate((doc.get("rallyPoints") or {}).get("points") or [], 1):
        rally.append(dict(where=f"rally point {number}", command=5100,
                          frame=MAV_FRAME_GLOBAL_RELATIVE_ALT, x=coordinate(point[0], 3),
                          y=coordinate(point[1], 3), z=f32(point[2]), mission_type=RALLY))
    for kind in (items, fence, rally):
        for seq, item in enumerate(kind):
            item["seq"] = seq
    return items, fence, rally, problems


# ---------------------------------------------------------------- comparing

def as_dict(item):
    if isinstance(item, dict):
        return item
    if isinstance(item, (list, tuple)):
        return dict(zip(FIELDS, item))
    return {name: getattr(item, name) for name in FIELDS}


def same(a, b):
    if isinstance(a, float) or isinstance(b, float):
        a, b = float(a), float(b)
        return (math.isnan(a) and math.isnan(b)) or a == b
    return a == b


def show(value):
    return repr(value) if not isinstance(value, float) else f"{value!r}"


def differences(expected, got, side, against="file"):
    """What `got` (items seen on `side`) has that differs from `expected`, in the fields
    that `expected` gives."""
    got = [as_dict(item) for item in got]
    found = []
    if len(got) != len(expected):
        found.append(f"{side} has {len(got)} items, {against} has {len(expected)}")
    for want, have in zip(expected, got):
        for name in FIELDS:
            if name in want and not same(want[name], have[name]):
                where = want.get("where", f"seq {want.get('seq')}")
                found.append(f"{side} {where} {name}: {against} {show(want[name])}, "
                             f"{side} {show(have[name])}")
    return found


# ---------------------------------------------------------------- the autopilot (child)

def autopilot_child(port, deadline):
    """A MAVSDK autopilot (MissionRawServer) on udpin://127.0.0.1:PORT that reports each
    mission it receives, and each MISSION_CLEAR_ALL, as a JSON line on stdout. It ends when
    its stdin closes or after `deadline` seconds, whichever is first."""
    lock = threading.Lock()

    def emit(event):
        with lock:
            sys.stdout.write(MARK + json.dumps(event) + "\n")
            sys.stdout.flush()

    def stdin_closed():
        try:
            sys.stdin.buffer.read()
        finally:
            os._exit(0)

    threading.Thread(target=stdin_closed, daemon=True).start()
    threading.Timer(deadline, lambda: os._exit(3)).start()
    try:
        from mavsdk import log_subscribe, LogLevel
        from mavsdk.asyncio import Mavsdk, Configuration, ComponentType
        from mavsdk.asyncio.plugins.mission_raw_server import MissionRawServerAsync
    except Exception as error:  # noqa: BLE001 (said to the parent, which fails)
        emit({"event": "error", "msg": f"cannot import mavsdk: {error!r}"})
        os._exit(2)

    def on_log(level, message, _file, _line):
        if level >= LogLevel.WARN:
            emit({"event": "log", "msg": message})
        return True  # MAVSDK prints nothing itself: stdout carries the protocol

    log_subscribe(on_log)

    async def main():
        autopilot = Mavsdk(Configuration.create_with_component_type(ComponentType.AUTOPILOT))
        await autopilot.add_any_connection(f"udpin://127.0.0.1:{port}")
        server = MissionRawServerAsync(await autopilot.server_component())

        async def incoming():
            async for result, plan in server.subscribe_incoming_mission():
                emit({"event": "mission", "result": int(result), "name": result.name,
                      "items": [[getattr(item, name) for name in FIELDS]
                                for item in plan.mission_items]})

        async def clears():
            async for mission_type in server.subscribe_clear_all():
                emit({"event": "clear", "type": int(mission_type)})

        tasks = [asyncio.ensure_future(incoming()), asyncio.ensure_future(clears())]
        await asyncio.sleep(0.2)  # let both subscriptions register
        emit({"event": "ready"})
        await asyncio.gather(*tasks)

    try:
        asyncio.run(main())
    except Exception as error:  # noqa: BLE001
        emit({"event": "error", "msg": repr(error)})
    os._exit(1)


# ---------------------------------------------------------------- the session (parent)

class Session:
    """One autopilot child process and one in-process MAVSDK ground station, reused for all
    files; restarted after a file that timed out or killed the autopilot."""

    def __init__(self, deadline):
        self.deadline = deadline
        self.proc = None
        self.gcs = None
        self.mission_raw = None
        self.events = None
        self.readers = []
        self.child_log = []  # the child's warnings and stderr, last lines
        self.gcs_log = []  # the ground station's warnings and errors
        self.home_first = False
        self.healthy = False
        self.step = "starting"  # what the current file is at, for a timeout's message

    async def start(self):
        from mavsdk.asyncio import Mavsdk, Configuration, ComponentType, Autopilot
        from mavsdk.asyncio.plugins.mission_raw import MissionRawAsync

        with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as probe:
            probe.bind(("127.0.0.1", 0))
            port = probe.getsockname()[1]
        self.events = asyncio.Queue()
        self.proc = await asyncio.create_subprocess_exec(
            sys.executable, os.path.abspath(__file__), "--autopilot-child", str(port),
            "--deadline", str(self.deadline), stdin=subprocess.PIPE,
            stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        self.readers = [asyncio.ensure_future(self._read_stdout()),
                        asyncio.ensure_future(self._read_stderr())]
        await self.wait_event("ready", START_TIMEOUT, "the autopilot to start")
        self.gcs = Mavsdk(Configuration.create_with_component_type(ComponentType.GROUND_STATION))
        await asyncio.wait_for(self.gcs.add_any_connection(f"udpout://127.0.0.1:{port}"),
                               STEP_TIMEOUT)
        seen = asyncio.ensure_future(self.gcs.first_autopilot(timeout_s=START_TIMEOUT))
        ended = asyncio.ensure_future(self.proc.wait())
        await asyncio.wait([seen, ended], timeout=START_TIMEOUT + 5,
                           return_when=asyncio.FIRST_COMPLETED)
        ended.cancel()
        if not seen.done():
            seen.cancel()
            tail = "; ".join(self.child_log[-3:])
            raise RuntimeError(f"autopilot process ended (exit {self.proc.returncode}) before "
                               f"the ground station saw it" + (f" ({tail})" if tail else ""))
        system = seen.result()
        if system is None:
            raise RuntimeError(f"ground station saw no autopilot on 127.0.0.1:{port} "
                               f"within {START_TIMEOUT:.0f} s")
        # MAVSDK's import puts plannedHomePosition first for ArduPilot only; its own
        # autopilot says MAV_AUTOPILOT_GENERIC, but follow whatever it reports.
        self.home_first = (await system.autopilot_type()) == Autopilot.ARDUPILOT
        self.mission_raw = MissionRawAsync(system)
        self.healthy = True

    async def _read_stdout(self):
        while True:
            line = await self.proc.stdout.readline()
            if not line:
                await self.events.put({"event": "exit"})
                return
            text = line.decode("utf-8", "replace").rstrip("\n")
            if not text.startswith(MARK):
                continue
            event = json.loads(text[len(MARK):])
            if event["event"] in ("log", "error"):
                self.child_log = (self.child_log + [event["msg"]])[-20:]
            if event["event"] != "log":
                await self.events.put(event)

    async def _read_stderr(self):
        while True:
            line = await self.proc.stderr.readline()
            if not line:
                return
            self.child_log = (self.child_log + [line.decode("utf-8", "replace").rstrip()])[-20:]

    def drain(self):
        while not self.events.empty():
            event = self.events.get_nowait()
            if event["event"] == "exit":
                self.events.put_nowait(event)
                return

    async def wait_event(self, kind, timeout, what):
        end = time.monotonic() + timeout
        while True:
            left = end - time.monotonic()
            if left <= 0:
                raise TimeoutError(f"no answer from the autopilot within {timeout:.0f} s "
                                   f"waiting for {what}")
            try:
                event = await asyncio.wait_for(self.events.get(), left)
            except asyncio.TimeoutError:
                continue
            if event["event"] in ("exit", "error"):
                self.healthy = False
                self.events.put_nowait(event)
                tail = "; ".join(self.child_log[-3:])
                raise RuntimeError(f"autopilot process ended while waiting for {what}"
                                   + (f" ({tail})" if tail else ""))
            if event["event"] == kind:
                return event

    async def stop(self):
        self.healthy = False
        gcs, self.gcs, self.mission_raw = self.gcs, None, None
        if gcs is not None:  # destroy joins MAVSDK's threads: bounded, in a daemon thread
            done = threading.Thread(target=gcs.destroy, daemon=True)
            done.start()
            done.join(5)
        proc, self.proc = self.proc, None
        if proc is not None and proc.returncode is None:
            try:
                proc.stdin.close()
                await asyncio.wait_for(proc.wait(), 3)
            except (asyncio.TimeoutError, OSError, ProcessLookupError):
                pass
            if proc.returncode is None:
                proc.kill()
                try:
                    await asyncio.wait_for(proc.wait(), 3)
                except asyncio.TimeoutError:
                    pass
        for reader in self.readers:
            reader.cancel()
        self.readers = []


def log_sink(session_holder):
    """MAVSDK's log, silenced: warnings and errors kept for the failure messages."""
    from mavsdk import log_subscribe, LogLevel

    def on_log(level, message, _file, _line):
        session = session_holder[0]
        if session is not None and level >= LogLevel.WARN:
            session.gcs_log = (session.gcs_log + [message])[-20:]
        return True

    log_subscribe(on_log)


# ---------------------------------------------------------------- one file

async def upload_and_compare(session, kind, items, expected, imported):
    """Upload `items` of one mission type; the autopilot must get the file's items, and
    exactly what MAVSDK imported, field for field."""
    raw = session.mission_raw
    calls = {MISSION: raw.upload_mission, FENCE: raw.upload_geofence,
             RALLY: raw.upload_rally_points}
    names = {MISSION: "mission", FENCE: "geofence", RALLY: "rally points"}
    session.step = f"uploading the {names[kind]}"
    session.drain()
    await asyncio.wait_for(calls[kind](items), STEP_TIMEOUT)
    event = await session.wait_event("mission", STEP_TIMEOUT,
                                     f"the {names[kind]} to arrive")
    if event["result"] != SERVER_SUCCESS:
        return [f"autopilot reported {event['name']} for the {names[kind]} upload"]
    got = event["items"]
    found = differences(expected, got, "autopilot")
    exact = [dict(as_dict(item), where=f"{names[kind]} seq {as_dict(item)['seq']}")
             for item in imported]
    found += differences(exact, got, "autopilot", against="import")
    return found


async def check_file(session, path, import_path=None, tamper=None):
    """(ok, problems, notes) for one .plan. `import_path` is what MAVSDK imports (default: the file
    itself); `tamper(kind, items)` may alter the items between import and upload. Both
    exist for --self-test only."""
    problems, notes = [], []
    session.step = "reading the file"
    session.gcs_log = []
    try:
        with open(path, encoding="utf-8") as handle:
            doc = json.load(handle)
    except (OSError, ValueError) as error:
        doc = None
        problems.append(f"file is not valid JSON ({error})")
    if doc is not None:
        mission, fence, rally, file_problems = expected_items(doc, session.home_first)
        problems += file_problems

    session.step = "importing with MissionRaw.import_qgroundcontrol_mission"
    try:
        data = await asyncio.wait_for(
            session.mission_raw.import_qgroundcontrol_mission(import_path or path),
            STEP_TIMEOUT)
    except asyncio.TimeoutError:
        raise
    except Exception as error:  # noqa: BLE001 (MissionRawError, or the binding's own)
        reason = getattr(getattr(error, "result", None), "name", None) or repr(error)
        said = "; ".join(session.gcs_log[-2:])
        problems.append(f"MAVSDK import failed: {reason}" + (f" ({said})" if said else ""))
        return False, problems, notes
    if problems:  # the file itself is wrong: no point in uploading it
        problems.append("MAVSDK's import accepted it all the same")
        return False, problems, notes

    problems += differences(mission, data.mission_items, "import")
    fence_supported = hasattr(data, "geofence_items") and hasattr(session.mission_raw,
                                                                  "upload_geofence")
    rally_supported = hasattr(data, "rally_items") and hasattr(session.mission_raw,
                                                               "upload_rally_points")
    if fence_supported:
        problems += differences(fence, data.geofence_items, "import")
    elif fence:
        notes.append("geofence import not supported by this mavsdk, not checked")
    if rally_supported:
        problems += differences(rally, data.rally_items, "import")
    elif rally:
        notes.append("rally point import not supported by this mavsdk, not checked")

    session.step = "clearing the autopilot's mission"
    session.drain()
    await asyncio.wait_for(session.mission_raw.clear_mission(), STEP_TIMEOUT)
    await session.wait_event("clear", STEP_TIMEOUT, "MISSION_CLEAR_ALL")

    uploads = [(MISSION, mission, data.mission_items)]
    if fence_supported and (fence or data.geofence_items):
        uploads.append((FENCE, fence, data.geofence_items))
    if rally_supported and (rally or data.rally_items):
        uploads.append((RALLY, rally, data.rally_items))
    for kind, expected, imported in uploads:
        items = [copy.copy(item) for item in imported]
        if tamper is not None:
            items = tamper(kind, items)
        problems += await upload_and_compare(session, kind, items, expected, imported)

    counts = f"{len(mission)} items"
    if fence:
        counts += f", {len(fence)} geofence items"
    if rally:
        counts += f", {len(rally)} rally point" + ("s" if len(rally) > 1 else "")
    notes.insert(0, counts)
    return not problems, problems, notes


async def run_file(session, path, name, **hooks):
    """Prints the file's line; returns whether it passed. Restarts a broken session."""
    if not session.healthy:
        await session.stop()
        try:
            await session.start()
        except Exception as error:  # noqa: BLE001
            print(f"mavsdk: {name}: FAILED: MAVSDK could not be restarted: {error}", flush=True)
            return False, [str(error)]
    try:
        ok, problems, notes = await asyncio.wait_for(check_file(session, path, **hooks),
                                                     FILE_TIMEOUT)
    except (asyncio.TimeoutError, TimeoutError) as error:
        session.healthy = False
        ok, problems, notes = False, [f"timed out {session.step}" + (f" ({error})" if str(
            error) else f" (at most {STEP_TIMEOUT:.0f} s a step, {FILE_TIMEOUT:.0f} s a file)")
        ], []
    except Exception as error:  # noqa: BLE001
        session.healthy = False
        if hasattr(error, "result") and hasattr(error, "origin"):  # MissionRawError
            said = "; ".join(session.gcs_log[-2:])
            text = f"MAVSDK {error.origin} gave {error.result.name} while {session.step}" + (
                f" ({said})" if said else "")
        else:
            text = f"{type(error).__name__} while {session.step}: {error}"
        ok, problems, notes = False, [text], []
    if ok:
        head, *rest = notes
        extra = f" ({'; '.join(rest)})" if rest else ""
        print(f"mavsdk: {name}: {head} uploaded unchanged{extra}", flush=True)
    else:
        shown = "; ".join(problems[:5])
        more = f"; and {len(problems) - 5} more" if len(problems) > 5 else ""
        print(f"mavsdk: {name}: FAILED: {shown}{more}", flush=True)
    return ok, problems


# ---------------------------------------------------------------- self-test

SYNTHETIC_PLAN = {
    "fileType": "Plan", "groundStation": "QGroundControl", "version": 1,
    "geoFence": {"version": 2, "circles": [
        {"inclusion": False, "version": 1,
         "circle": {"center": [-10.4945, 105.6262], "radius": 12.5}}],
        "polygons": [
            {"inclusion": True, "version": 1, "polygon": [
                [-10.49490575, 105.62598435], [-10.49490467, 105.62653264],
                [-10.49436204, 105.62653155], [-10.49436312, 105.62598326]]},
            {"inclusion": False, "version": 1, "polygon": [
                [-10.4946, 105.6261], [-10.4946, 105.6263], [-10.4944, 105.6262]]}]},
    "rallyPoints": {"version": 2, "points": [[-10.493925159, 105.621817232, 30.0]]},
    "mission": {
        "version": 2, "firmwareType": 3, "vehicleType": 2, "globalPlanAltitudeMode": 1,
        "cruiseSpeed": 6.0, "hoverSpeed": 3.0,
        "plannedHomePosition": [-10.493925159, 105.621817232, 160.845],
        "items": [
            {"type": "SimpleItem", "autoContinue": True, "command": 22, "doJumpId": 1,
             "frame": 3, "params": [0.0, 0.0, 0.0, None, -10.493925159, 105.621817232, 17.5]},
            {"type": "SimpleItem", "autoContinue": True, "command": 178, "doJumpId": 2,
             "frame": 2, "params": [1.0, 8.0, -1.0, 0.0, 0.0, 0.0, 0.0]},
            {"type": "SimpleItem", "autoContinue": True, "command": 16, "doJumpId": 3,
             "frame": 0, "params": [0.0, 1.0, 0.0, None, -10.49490575, 105.62598435, 178.345]},
            {"type": "SimpleItem", "autoContinue": True, "command": 16, "doJumpId": 4,
             "frame": 10, "params": [0.0, 1.0, 0.0, None, -10.49490467, 105.62653264, 2.5]},
            {"type": "SimpleItem", "autoContinue": True, "command": 183, "doJumpId": 5,
             "frame": 0, "params": [9.0, 1900.0, 0.0, 0.0, 0.0, 0.0, 0.0]},
            {"type": "SimpleItem", "autoContinue": False, "command": 16, "doJumpId": 6,
             "frame": 3, "params": [0.5, 1.0, 0.0, 90.0, -10.49436204, 105.62653155, 3.1]},
            {"type": "SimpleItem", "autoContinue": True, "command": 21, "doJumpId": 7,
             "frame": 3, "params": [0.0, 0.0, 0.0, None, -10.493925159, 105.621817232, 0.0]},
        ]},
}


def altered_copy(doc, folder, name, change):
    doc = copy.deepcopy(doc)
    change(doc)
    path = os.path.join(folder, name)
    with open(path, "w", encoding="utf-8") as handle:
        json.dump(doc, handle, indent=2)
    return path


def bump_nav_altitude(doc):
    for item in doc["mission"]["items"]:
        if item["command"] == 16 and item["params"][6]:
            item["params"][6] += 1.5
            return


def drop_a_param(doc):
    doc["mission"]["items"][2]["params"] = doc["mission"]["items"][2]["params"][:6]


async def self_test(session, base_plans, folder):
    """Cases, each expected to pass or to be caught. Returns (passed, failed)."""
    cases = []
    for label, path in base_plans:
        with open(path, encoding="utf-8") as handle:
            doc = json.load(handle)
        altered = altered_copy(doc, folder, f"altered-{os.path.basename(path)}",
                               bump_nav_altitude)

        def raise_z(kind, items):
            for item in items:
                if kind == MISSION and item.command == 16:
                    item.z += 0.25
                    break
            return items

        def change_frame(kind, items):
            if kind == MISSION:
                items[-1].frame = 10 if items[-1].frame != 10 else 3
            return items

        def drop_last(kind, items):
            return items[:-1] if kind == MISSION else items

        cases += [
            (f"{label}: as written", dict(path=path), True, None),
            (f"{label}: altered copy fed only to the MAVSDK import",
             dict(path=path, import_path=altered), False, "import item"),
            (f"{label}: one altitude raised between import and upload",
             dict(path=path, tamper=raise_z), False, "autopilot item"),
            (f"{label}: last item's frame changed between import and upload",
             dict(path=path, tamper=change_frame), False, "frame"),
            (f"{label}: last item dropped on upload",
             dict(path=path, tamper=drop_last), False, "autopilot has"),
        ]
    synthetic = altered_copy(SYNTHETIC_PLAN, folder, "synthetic.plan", lambda doc: None)

    def move_vertex(kind, items):
        if kind == FENCE:
            items[1].x += 1
        return items

    def rally_altitude(kind, items):
        if kind == RALLY:
            items[0].z = 31.0
        return items

    six = altered_copy(SYNTHETIC_PLAN, folder, "six-params.plan", drop_a_param)
    corrupt = os.path.join(folder, "corrupt.plan")
    with open(synthetic, encoding="utf-8") as handle, open(corrupt, "w") as out:
        out.write(handle.read()[:400])
    cases += [
        ("synthetic plan (frames 0/2/3/10, null params, fence, rally): as written",
         dict(path=synthetic), True, None),
        ("fence vertex moved 1e-7 deg on upload", dict(path=synthetic, tamper=move_vertex),
         False, "fence polygon 1 vertex 2 x"),
        ("rally point altitude changed on upload", dict(path=synthetic, tamper=rally_altitude),
         False, "rally point 1 z"),
        ("item with 6 params", dict(path=six), False, "6 params"),
        ("truncated JSON", dict(path=corrupt), False, "not valid JSON"),
    ]
    passed = failed = 0
    for name, hooks, should_pass, needle in cases:
        path = hooks.pop("path")
        print(f"mavsdk: self-test {name}:", flush=True)
        ok, problems = await run_file(session, path, "  " + os.path.basename(path), **hooks)
        caught = not ok and any(needle in problem for problem in problems)
        if (ok and should_pass) or (not should_pass and caught):
            passed += 1
            print(f"mavsdk:   -> as expected ({'passes' if should_pass else 'caught'})")
        else:
            failed += 1
            print(f"mavsdk:   -> WRONG: expected {'a pass' if should_pass else repr(needle)}")
    return passed, failed


# ---------------------------------------------------------------- main

def plan_files(folders):
    found = []
    for folder in folders:
        paths = sorted(glob.glob(os.path.join(folder, "**", "*.plan"), recursive=True))
        for path in paths:
            name = os.path.relpath(path, folder)
            found.append((path, name if len(folders) == 1 else os.path.join(folder, name)))
        if not paths:
            found.append((None, folder))
    return found


async def main_async(args):
    files = plan_files(args.dirs)
    try:
        import mavsdk
        version = getattr(mavsdk, "__version__", "?")
        from mavsdk.asyncio.plugins.mission_raw import MissionRawAsync  # noqa: F401
        from mavsdk.asyncio.plugins.mission_raw_server import MissionRawServerAsync  # noqa: F401
    except Exception as error:  # noqa: BLE001
        print(f"mavsdk: cannot run: the native MAVSDK binding (pip install 'mavsdk>=4.1,<5') "
              f"is not importable: {error}")
        return 0, max(1, len(files))

    holder = [None]
    log_sink(holder)
    session = Session(deadline=START_TIMEOUT * 2 + FILE_TIMEOUT * (len(files) + 12))
    holder[0] = session
    started = time.monotonic()
    passed = failed = 0
    try:
        try:
            await session.start()
        except Exception as error:  # noqa: BLE001
            tail = "; ".join(session.child_log[-3:])
            print(f"mavsdk: cannot run: MAVSDK {version} autopilot/ground station did not "
                  f"start: {type(error).__name__}: {error}" + (f" ({tail})" if tail else ""))
            return 0, max(1, len(files))
        ap = "ArduPilot" if session.home_first else "generic"
        print(f"mavsdk: MAVSDK {version}, ground station -> {ap} autopilot (MissionRawServer) "
              f"over UDP 127.0.0.1", flush=True)
        if args.self_test:
            folder = tempfile.mkdtemp(prefix="mavsdk-oracle-")
            try:
                bases = [(name, path) for path, name in files if path][:1]
                passed, failed = await self_test(session, bases, folder)
            finally:
                shutil.rmtree(folder, ignore_errors=True)
        else:
            for path, name in files:
                if path is None:
                    print(f"mavsdk: {name}: FAILED: no .plan files under it")
                    failed += 1
                    continue
                ok, _ = await run_file(session, path, name)
                passed += ok
                failed += not ok
        print(f"mavsdk: checked in {time.monotonic() - started:.1f} s", flush=True)
    finally:
        await session.stop()
    return passed, failed


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("dirs", nargs="*", help="folders whose *.plan files are checked")
    parser.add_argument("--self-test", action="store_true",
                        help="show that altered items are caught (DIRs optional)")
    parser.add_argument("--autopilot-child", type=int, help=argparse.SUPPRESS)
    parser.add_argument("--deadline", type=float, default=600.0, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.autopilot_child is not None:
        autopilot_child(args.autopilot_child, args.deadline)
        return
    if not args.dirs and not args.self_test:
        parser.error("give at least one folder of .plan files, or --self-test")
    # Not asyncio.run: its executor shutdown would wait for a MAVSDK call stuck past its
    # timeout.
    loop = asyncio.new_event_loop()
    passed, failed = loop.run_until_complete(main_async(args))
    print(f"mavsdk: {passed} passed, {failed} failed", flush=True)
    sys.stdout.flush()
    # MAVSDK's threads (and any call stuck past its timeout) must not hold the exit.
    os._exit(1 if failed or not passed else 0)


if __name__ == "__main__":
    main()

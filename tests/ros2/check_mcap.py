"""Checks a `poinav simulate --mcap` recording against the run's trace and Nav2 map.

Usage: check_mcap.py RECORDING.mcap TRACE.jsonl MAP.pgm MAP.yaml DT

Decodes every message twice, with `mcap` + `mcap-ros2-support` (the schemas stored in the
file) and with `rosbags` (AnyReader on the bare .mcap file, no metadata.yaml needed), and
asserts: profile `ros2`, `ros2msg` schemas, `cdr` messages; the topic list; message counts
(scan and odometry: one per trace line of the robot, /tf one per step, /map one, events one
per trace event); LaserScan ranges equal to the trace's ray distances (as float32; the +-60
degree beams NaN); odometry poses equal to the trace's; log times = start + step x dt; the
OccupancyGrid equal to the Nav2 map (map.pgm in trinary mode: 254 -> 0, 0 -> 100,
205 -> -1, rows bottom-up); /map and /poi/markers offered as transient local.
Prints a JSON summary; exits 1 with the first difference.
"""

import json
import math
import struct
import sys
from collections import Counter, defaultdict
from pathlib import Path

from mcap.reader import make_reader
from mcap_ros2.decoder import DecoderFactory
from rosbags.highlevel import AnyReader
from rosbags.interfaces import QosDurability

START_NS = 1_735_689_600_000_000_000
BEAM_OF_DEG = {-90: 0, -30: 2, 0: 3, 30: 4, 90: 6}


def fail(msg):
    print(msg, file=sys.stderr)
    sys.exit(1)


def f32(x):
    return struct.unpack("<f", struct.pack("<f", x))[0]


def read_pgm(path):
    data = Path(path).read_bytes()
    fields, i = [], 0
    while len(fields) < 4:
        while data[i : i + 1].isspace():
            i += 1
        if data[i : i + 1] == b"#":
            while data[i : i + 1] != b"\n":
                i += 1
            continue
        j = i
        while not data[j : j + 1].isspace():
            j += 1
        fields.append(data[i:j])
        i = j
    i += 1
    assert fields[0] == b"P5", fields[0]
    w, h = int(fields[1]), int(fields[2])
    return w, h, data[i : i + w * h]


def read_yaml(path):
    out = {}
    for line in Path(path).read_text().splitlines():
        k, _, v = line.partition(":")
        out[k.strip()] = v.strip()
    return out


def main():
    mcap_path, trace_path, pgm_path, yaml_path, dt = sys.argv[1:6]
    dt = float(dt)
    lines = [json.loads(x) for x in Path(trace_path).read_text().splitlines() if x.strip()]
    robots = list(dict.fromkeys(x["robot"] for x in lines))
    steps = sorted({x["step"] for x in lines})
    per_robot = defaultdict(list)
    for x in lines:
        per_robot[x["robot"]].append(x)
    events = [e for x in lines for e in x["events"]]

    def stamp(step):
        return START_NS + round(step * dt * 1e9)

    want_topics = {"/map", "/tf", "/poi/markers", "/poi/events"}
    for r in robots:
        want_topics |= {f"/{r}/scan", f"/{r}/odom"}

    # 1. mcap + mcap-ros2-support: every message decoded with the file's own schemas.
    decoded = defaultdict(list)
    with open(mcap_path, "rb") as f:
        reader = make_reader(f, decoder_factories=[DecoderFactory()])
        header = reader.get_header()
        if header.profile != "ros2":
            fail(f"profile {header.profile!r}, not ros2")
        summary = reader.get_summary()
        topics = {c.topic for c in summary.channels.values()}
        if topics != want_topics:
            fail(f"topics {sorted(topics)} != {sorted(want_topics)}")
        meta = {m.name: m.metadata for m in reader.iter_metadata()}
        if meta.get("rosbag2", {}).get("ROS_DISTRO") != "jazzy":
            fail(f"metadata records {meta}")
        for s in summary.schemas.values():
            if s.encoding != "ros2msg":
                fail(f"schema {s.name} encoded {s.encoding}")
        qos = {}
        for c in summary.channels.values():
            if c.message_encoding != "cdr":
                fail(f"{c.topic} messages are {c.message_encoding}")
            qos[c.topic] = c.metadata["offered_qos_profiles"]
        for schema, channel, message, ros in reader.iter_decoded_messages(log_time_order=False):
            decoded[channel.topic].append((message.log_time, ros, schema.name))

    counts = {t: len(v) for t, v in decoded.items()}
    want_counts = {"/map": 1, "/tf": len(steps), "/poi/events": len(events)}
    for r in robots:
        want_counts[f"/{r}/scan"] = len(per_robot[r])
        want_counts[f"/{r}/odom"] = len(per_robot[r])
    for t, n in want_counts.items():
        if counts.get(t, 0) != n:
            fail(f"{t}: {counts.get(t, 0)} messages, want {n}")
    if counts.get("/poi/markers", 0) < 1:
        fail("no /poi/markers")

    # 2. Scans and odometry equal the trace.
    checked_ranges = 0
    for r in robots:
        scans = decoded[f"/{r}/scan"]
        odoms = decoded[f"/{r}/odom"]
        for line, (t_scan, scan, _), (t_odom, odom, _) in zip(per_robot[r], scans, odoms):
            want_t = stamp(line["step"])
            if t_scan != want_t or t_odom != want_t:
                fail(f"{r} step {line['step']}: log time {t_scan} != {want_t}")
            st = scan.header.stamp
            if st.sec * 1_000_000_000 + st.nanosec != want_t:
                fail(f"{r} step {line['step']}: header stamp differs from log time")
            if scan.header.frame_id != f"{r}/base_link":
                fail(f"scan frame {scan.header.frame_id}")
            if len(scan.ranges) != 7 or abs(scan.angle_min + math.pi / 2) > 1e-6:
                fail(f"scan layout: {len(scan.ranges)} beams from {scan.angle_min}")
            if abs(scan.angle_increment - math.pi / 6) > 1e-6 or scan.range_max != 5.0:
                fail(f"scan increment {scan.angle_increment}, range_max {scan.range_max}")
            if not (math.isnan(scan.ranges[1]) and math.isnan(scan.ranges[5])):
                fail("the +-60 degree beams must be NaN")
            for ray in line["rays"]:
                got = scan.ranges[BEAM_OF_DEG[round(ray["deg"])]]
                want = f32(ray["d"]) if ray["d"] is not None else float("nan")
                if not (got == want or (math.isnan(got) and math.isnan(want))):
                    fail(f"{r} step {line['step']} ray {ray['deg']}: {got} != {want}")
                checked_ranges += 1
            p = odom.pose.pose.position
            if (p.x, p.y) != (line["x"], line["y"]):
                fail(f"{r} step {line['step']}: odom at {p.x},{p.y}, trace {line['x']},{line['y']}")
            q = odom.pose.pose.orientation
            yaw = math.degrees(2 * math.atan2(q.z, q.w))
            if abs((yaw - line["heading_deg"] + 180) % 360 - 180) > 1e-6:
                fail(f"{r} step {line['step']}: yaw {yaw} != {line['heading_deg']}")
            if abs(odom.twist.twist.linear.x - line["speed"]) > 1e-9:
                fail(f"{r} step {line['step']}: speed differs")
    tfs = decoded["/tf"]
    for (t, tf, _), step in zip(tfs, steps):
        frames = [(x.header.frame_id, x.child_frame_id) for x in tf.transforms]
        want = [("map", "odom")] + [("odom", f"{r}/base_link") for r in robots]
        if t != stamp(step) or frames != want:
            fail(f"/tf at step {step}: {frames} at {t}")
    for (_, msg, _), want in zip(decoded["/poi/events"], events):
        got = json.loads(msg.data)
        if got["kind"] != want["kind"]:
            fail(f"event {got} != {want}")

    # 3. The occupancy grid equals the Nav2 map.
    (_, grid, _), = decoded["/map"]
    w, h, pixels = read_pgm(pgm_path)
    meta = read_yaml(yaml_path)
    info = grid.info
    if (info.width, info.height) != (w, h):
        fail(f"grid {info.width}x{info.height}, map.pgm {w}x{h}")
    if abs(info.resolution - float(meta["resolution"])) > 1e-7:
        fail(f"resolution {info.resolution} != {meta['resolution']}")
    ox, oy, _ = (float(v) for v in meta["origin"].strip("[]").split(","))
    if abs(info.origin.position.x - ox) > 1e-6 or abs(info.origin.position.y - oy) > 1e-6:
        fail(f"origin {info.origin.position} != {ox},{oy}")
    value = {254: 0, 0: 100, 205: -1}
    want_data = [value[pixels[(h - 1 - row) * w + col]] for row in range(h) for col in range(w)]
    if list(grid.data) != want_data:
        diff = sum(a != b for a, b in zip(grid.data, want_data))
        fail(f"occupancy grid differs from map.pgm in {diff} cells")
    occ = Counter(want_data)

    # 4. rosbags reads the bare file too, with the latched topics transient local.
    rb_counts = Counter()
    with AnyReader([Path(mcap_path)]) as reader:
        for conn in reader.connections:
            profiles = conn.ext.offered_qos_profiles
            latched = conn.topic in ("/map", "/poi/markers")
            durable = profiles and profiles[0].durability == QosDurability.TRANSIENT_LOCAL
            if latched != bool(durable):
                fail(f"{conn.topic}: offered QoS {profiles}")
        for conn, _t, raw in reader.messages():
            reader.deserialize(raw, conn.msgtype)
            rb_counts[conn.topic] += 1
    if dict(rb_counts) != {t: n for t, n in counts.items() if n}:
        fail(f"rosbags counts {dict(rb_counts)} != mcap counts {counts}")

    print(
        json.dumps(
            {
                "topics": sorted(topics),
                "counts": counts,
                "robots": robots,
                "steps": len(steps),
                "ranges_checked": checked_ranges,
                "map": {"width": w, "height": h, "free": occ[0], "occupied": occ[100], "unknown": occ[-1]},
                "qos_map": qos["/map"].splitlines()[3].strip(),
            },
            sort_keys=True,
        )
    )


if __name__ == "__main__":
    main()

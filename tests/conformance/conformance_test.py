#!/usr/bin/env python3
"""Protocol conformance: a Python client written from docs/PROTOCOL.md against a real server.

Starts build/bin/foresight-server (--scene maze) on a free port and checks, as an independent
implementation would: the document's own test vectors (AEAD, packed avatars), the handshake,
sealed inputs, walking, packed avatars decoded equal to a whole-state client's, the tree summary,
dropped bad datagrams, a clean disconnect. Exits 0 when every check passes, 1 when one fails,
77 (ctest's SKIP_RETURN_CODE) when python3-flatbuffers or python3-nacl is missing.

  conformance_test.py --server build/bin/foresight-server --schema schema/foresight.fbs \
      [--generated build/tests/conformance/python] [--flatc flatc]
"""

import argparse
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import urllib.request

SKIP = 77

try:
    import flatbuffers  # noqa: F401  (python3-flatbuffers)
    import nacl.bindings  # noqa: F401  (python3-nacl)
except ImportError as e:
    print(f"conformance: SKIPPED: {e}: install Debian's python3-flatbuffers and python3-nacl "
          f"(scripts/install-deps) for {sys.executable}", flush=True)
    sys.exit(SKIP)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import foresight_client as fc  # noqa: E402

failures = []


def check(ok, what, detail=""):
    print(f"  {'ok  ' if ok else 'FAIL'} {what}{(': ' + str(detail)) if detail != '' else ''}", flush=True)
    if not ok:
        failures.append(what)
    return ok


def section(title):
    print(f"\n== {title}", flush=True)


# ---------------------------------------------------------------------------------------------
# Generated classes

def generated_folder(args, tmp):
    """The build's flatc output, or (missing or older than the schema) a fresh one in tmp."""
    packet = os.path.join(args.generated or "", "foresight", "wire", "Packet.py")
    if args.generated and os.path.exists(packet) and \
            os.path.getmtime(packet) >= os.path.getmtime(args.schema):
        return args.generated
    out = os.path.join(tmp, "python")
    flatc = shutil.which(args.flatc) or args.flatc
    print(f"conformance: generating the message classes with {flatc} into {out}", flush=True)
    subprocess.run([flatc, "--python", "-o", out, args.schema], check=True)
    return out


# ---------------------------------------------------------------------------------------------
# The document's vectors, offline

def hexbytes(s):
    return bytes.fromhex(" ".join(s.split()))


def check_document_vectors():
    section("PROTOCOL.md's own vectors (offline)")
    # "Sealed sessions": the AEAD test vector.
    key = bytes(range(32))
    plain = hexbytes("""10 00 00 00 46 53 47 31 08 00 0c 00 07 00 08 00 08 00 00 00 00 00 00 07 0c 00 00 00
        08 00 0c 00 04 00 08 00 08 00 00 00 04 03 02 01 e8 03 00 00""")
    payload = hexbytes("""8f 57 f3 5f f3 79 e8 29 21 b6 a2 5c 55 95 91 87 cd 7d eb 0e 47 6b 60 aa cf 64 b5 5b
        85 e8 d1 a4 dc 4a de ac ec c8 df 8b 80 28 f6 9e 63 87 9c 6d 0b fa c0 30 dd c6 46 83
        7c d4 6a 74 7d f2 2d 9c""")
    check(fc.nonce_of(1) == hexbytes("00 00 00 00 01 00 00 00 00 00 00 00"), "nonce of sequence 1")
    check(fc.ad_of(0x01020304) == hexbytes("04 03 02 01"), "additional data of session 0x01020304")
    check(fc.seal_payload(key, 0x01020304, 1, plain) == payload, "AEAD test vector seals to the documented payload")
    check(fc.open_payload(key, 0x01020304, 1, payload) == plain, "and opens back")
    check(fc.open_payload(key, 0x01020305, 1, payload) is None, "another session id (additional data) does not open")
    check(fc.open_payload(key, 0x01020304, 2, payload) is None, "another sequence (nonce) does not open")
    p = fc.read_packet(plain)
    hb = fc.table_of(p, "Heartbeat")
    check(p.MessageType() == fc.HEARTBEAT and hb.Session() == 0x01020304 and hb.ClientTimeMs() == 1000,
          "the vector's plaintext reads as Heartbeat{0x01020304, 1000}")
    sealed = fc.read_packet(fc.make_sealed(0x01020304, 1, payload))
    st = fc.table_of(sealed, "Sealed")
    check(sealed.MessageType() == fc.SEALED and st.Session() == 0x01020304 and st.Sequence() == 1 and
          fc.vector_bytes(st, 2) == payload, "a Sealed around it reads back")

    # "Packed avatars": the worked examples (protocol 8: written with a 6-bit "snapshots back").
    whole = {"id": 1, "segment": 3, "transition": -1, "start_x_mm": 1000, "start_z_mm": -500,
             "start_heading": 16384, "frame": 4, "flags": 0x01, "reserved": 0}
    got = fc.decode_avatars(hexbytes("02 80 5e a0 57 ce 03 00 b1 80"), 1, 10, {})
    check(got == [whole], "worked example 1 (whole) decodes", got)
    history = {10: {1: whole}}
    got = fc.decode_avatars(hexbytes("02 48 40 f4 01"), 1, 11, history)
    check(got == [dict(whole, frame=7)], "worked example 2 (same play-through, frame as predicted) decodes", got)
    got = fc.decode_avatars(hexbytes("62 48 40 94 56 b0 00 08 f2"), 1, 11, history)
    check(got == [dict(whole, segment=2, transition=5, start_x_mm=1300, start_heading=16484, frame=0)],
          "worked example 3 (a new segment) decodes", got)
    try:
        fc.decode_avatars(hexbytes("02 48 40 f4 01"), 1, 11, {})
        check(False, "a reference to a snapshot not held is missing_baseline")
    except fc.MissingBaseline:
        check(True, "a reference to a snapshot not held is missing_baseline")
    try:
        fc.decode_avatars(hexbytes("02 80 5e a0 57 ce 03 00 b1 80 00"), 1, 10, {})
        check(False, "a byte left over is invalid")
    except fc.ProtocolError as e:
        check(e.reason == "invalid_input", "a byte left over is invalid", e.reason)


# ---------------------------------------------------------------------------------------------
# The server

class Server:
    def __init__(self, binary, tmp):
        self.port = fc.free_port()
        self.admin_port = fc.free_port(fc.socket.SOCK_STREAM)
        self.token = "conformance"
        self.log_path = os.path.join(tmp, "server.log")
        self.log = open(self.log_path, "w")
        cmd = [binary, "--scene", "maze", "--bind", "127.0.0.1", "--port", str(self.port),
               "--admin-port", str(self.admin_port), "--admin-token", self.token,
               "--status-every-s", "0", "--seconds", "120"]
        print("conformance: " + " ".join(cmd), flush=True)
        self.proc = subprocess.Popen(cmd, stdout=self.log, stderr=subprocess.STDOUT)
        self.address = ("127.0.0.1", self.port)

    def metrics(self):
        req = urllib.request.Request(f"http://127.0.0.1:{self.admin_port}/metrics",
                                     headers={"Authorization": f"Bearer {self.token}"})
        text = urllib.request.urlopen(req, timeout=5).read().decode()
        out = {}
        for line in text.splitlines():
            if line and not line.startswith("#"):
                name, _, value = line.rpartition(" ")
                out[name] = float(value)
        return out

    def wait_ready(self, timeout_s=15):
        end = time.monotonic() + timeout_s
        while time.monotonic() < end:
            if self.proc.poll() is not None:
                raise RuntimeError(f"the server exited ({self.proc.returncode}): {self.log_text()}")
            try:
                urllib.request.urlopen(f"http://127.0.0.1:{self.admin_port}/readyz", timeout=1)
                return
            except Exception:  # noqa: BLE001 - not up yet
                time.sleep(0.1)
        raise TimeoutError("the server did not get ready")

    def log_text(self):
        if not self.log.closed:
            self.log.flush()
        with open(self.log_path) as f:
            return f.read()

    def stop(self):
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGTERM)
            try:
                self.proc.wait(timeout=10)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        self.log.close()


def drop_metric(m, reason):
    return m.get(f'foresight_packets_dropped_total{{reason="{reason}"}}', 0)


# ---------------------------------------------------------------------------------------------
# Against the server

def run(server):
    h = fc.Harness()

    section("handshake refusals in the clear")
    probe = h.add(fc.Client(server.address, "probe"))
    before = server.metrics()
    probe.send_raw(fc.make_connect_request(fc.PROTOCOL_VERSION + 1000, 0, "probe"))
    h.until(lambda: probe.refusals, 3, "a Refuse to another protocol version")
    reason, message, server_hash = probe.refusals[0]
    check(reason == "ProtocolVersion", "another protocol version: Refuse ProtocolVersion", message)
    check(server_hash != 0, "every Refuse carries the server's library hash", f"{server_hash:016x}")
    probe.send_raw(fc.make_connect_request(fc.PROTOCOL_VERSION, 0, "probe", padding=0))
    h.pump(0.3, send=False)
    after = server.metrics()
    check(len(probe.refusals) == 1 and fc.CHALLENGE not in probe.received,
          "an unpadded ConnectRequest gets no answer")
    check(drop_metric(after, "too_small") - drop_metric(before, "too_small") == 1,
          "and is dropped as too_small")
    h.clients.remove(probe)
    probe.close()

    section("handshake: ConnectRequest, Challenge, ConnectResponse, Refuse Library, Accept")
    a = h.add(fc.Client(server.address, "walker"))
    t0 = time.monotonic()
    acc = a.connect(h)
    check(True, "connected", f"{1000 * (time.monotonic() - t0):.0f} ms, {acc}")
    check(a.received.get(fc.CHALLENGE, 0) >= 1, "a Challenge came in the clear")
    check(len(a.cookie) == 8, "its cookie is 8 bytes", len(a.cookie))
    check(any(r[0] == "Library" for r in a.refusals), "library hash 0 refused as Library")
    check(acc["library_hash"] == server_hash == a.library_hash, "the Accept's library hash is the Refuse's")
    check(acc["session"] >= 1 and len(acc["server_key"]) == 32, "session id and 32-byte server key")
    check(acc["scene"] == "maze" and acc["tick_hz"] == 30 and acc["snapshot_hz"] == 20,
          "scene maze, 30 Hz ticks, 20 Hz snapshots", (acc["scene"], acc["tick_hz"], acc["snapshot_hz"]))
    b = h.add(fc.Client(server.address, "watcher", acknowledge=False, library_hash=server_hash))
    accb = b.connect(h)
    check(accb["session"] != acc["session"] and accb["avatar"] != acc["avatar"],
          "a second client (whole states, acknowledges nothing) connected", accb["session"])
    check(not any(r[0] == "Library" for r in b.refusals), "with the right hash at once: no Library refusal")

    section("sealed session: snapshots and inputs")
    h.until(lambda: len(a.whole_order) >= 5 and len(b.whole_order) >= 5, 3, "snapshots")
    check(a.received.get(fc.SNAPSHOT, 0) == 0 and a.received.get(100 + fc.SNAPSHOT, 0) > 0,
          "snapshots come sealed, never in the clear", a.received.get(100 + fc.SNAPSHOT, 0))
    ticks = a.whole_order[-5:]
    check(all(fc.int32(y - x) == 1 for x, y in zip(ticks, ticks[1:])), "Snapshot.tick counts one a snapshot", ticks)
    check(a.own() is not None and a.own()["flags"] & fc.AVATAR_YOURS, "own avatar in snapshots, flagged kAvatarYours")

    section("walking")
    start_walk = dict(a.own())
    a.camera_yaw = 16384      # the camera looks towards +X
    a.dir = (0, 127)          # forward
    stats0 = server.metrics()
    h.pump(1.5)
    a.request(fc.TREE_REQUEST)
    b.request(fc.STATS_REQUEST)
    h.until(lambda: a.trees and b.stats, 2, "a TreeSummary and ServerStats")
    tree_seen_ticks = list(a.whole_order[-12:])
    h.pump(1.5)
    end_walk = a.own()
    dx = end_walk["start_x_mm"] - start_walk["start_x_mm"]
    dz = end_walk["start_z_mm"] - start_walk["start_z_mm"]
    dist = (dx * dx + dz * dz) ** 0.5
    check(dist >= 500, "3 s walking moved the own avatar's segment start by 0.5 m or more",
          f"{dist / 1000:.2f} m: ({dx}, {dz}) mm")
    check(dx > abs(dz), "towards +X, where camera yaw 16384 looks", f"({dx}, {dz}) mm")
    check(end_walk["segment"] != start_walk["segment"] or end_walk["start_x_mm"] != start_walk["start_x_mm"],
          "it plays other segments")
    newest_command = a.next_command - 1
    check(a.ack_input > 0 and 0 <= newest_command - a.ack_input <= 30,  # 30: 1 s of commands
          "Snapshot.ack_input follows the sealed inputs",
          f"sent {newest_command}, applied {a.ack_input}")
    check(a.echo_ms is not None and 0 <= (fc.now_ms() - a.echo_ms) & 0xFFFFFFFF < 1000,
          "echo_client_time_ms echoes our clock", a.echo_ms)
    check(b.state == "connected" and b.echo_ms is not None, "the heartbeat-only client stays in session")

    section("packed avatars: the acknowledging client against the whole-state client")
    # The same world by the server's time: each client numbers its own snapshots.
    common = sorted(set(a.at_server_ms) & set(b.at_server_ms))
    mismatches = []
    for t in common:
        va, vb = a.at_server_ms[t], b.at_server_ms[t]
        if set(va) != set(vb):
            mismatches.append((t, "ids", sorted(va), sorted(vb)))
            continue
        for i in va:
            for f in fc.AVATAR_FIELDS:
                x, y = va[i][f], vb[i][f]
                if f == "flags":
                    x, y = x & ~fc.AVATAR_YOURS, y & ~fc.AVATAR_YOURS
                if x != y:
                    mismatches.append((t, i, f, x, y))
    # About a third of the ticks serve both clients (each is served on two of three): ~10 a second.
    check(len(common) >= 20, "snapshots decoded by both", len(common))
    check(not mismatches, "every avatar of every common snapshot equal, field by field", mismatches[:5])
    both = [t for t in common if acc["avatar"] in a.at_server_ms[t] and accb["avatar"] in a.at_server_ms[t]]
    check(len(both) >= 20 and all(a.at_server_ms[t][acc["avatar"]]["flags"] & fc.AVATAR_YOURS and
                                  not b.at_server_ms[t][acc["avatar"]]["flags"] & fc.AVATAR_YOURS and
                                  b.at_server_ms[t][accb["avatar"]]["flags"] & fc.AVATAR_YOURS for t in both),
          "kAvatarYours set on each receiver's own avatar only", len(both))
    check(a.kinds.get("same_predicted", 0) > 0 and a.kinds.get("new_segment", 0) > 0,
          "the acknowledging client got delta-coded records (same play-through and new segments)", a.kinds)
    check(set(b.kinds) == {"whole"} and not any(b.ref_counts), "the other got whole states only", b.kinds)
    check(not a.drops and not b.drops, "neither client dropped anything", (a.drops, b.drops))
    stats1 = server.metrics()
    delta = stats1["foresight_snapshot_avatars_delta_total"] - stats0["foresight_snapshot_avatars_delta_total"]
    check(delta >= a.kinds.get("same_predicted", 0) // 2, "the server counts delta-coded avatars", delta)

    section("tree summary")
    tree = a.trees[0]
    s = tree["sampled"]
    check(tree["avatar"] == acc["avatar"], "the requester's own avatar", tree["avatar"])
    check(1 <= len(s) <= fc.MAX_TREE_SAMPLES, f"1 to {fc.MAX_TREE_SAMPLES} samples", len(s))
    check(tree["nodes"] >= len(s), "nodes in the tree >= samples", (tree["nodes"], len(s)))
    check(s[0]["parent"] == fc.TREE_NO_PARENT and s[0]["depth"] == 0, "sampled[0] is the root")
    check(all(0 <= n["parent"] < j and n["depth"] == s[n["parent"]]["depth"] + 1 for j, n in enumerate(s) if j),
          "every parent comes before its node, one level up")
    chosen = [j for j, n in enumerate(s) if n["flags"] & fc.TREE_NODE_CHOSEN]
    check(chosen == list(range(1, len(chosen) + 1)) and all(s[j]["parent"] == j - 1 for j in chosen),
          "the chosen branch comes right after the root (not flagged itself), each node the child "
          "of the one before", chosen)
    origins = {(a.keep_all[t][acc["avatar"]]["start_x_mm"], a.keep_all[t][acc["avatar"]]["start_z_mm"])
               for t in tree_seen_ticks + a.whole_order[-40:] if acc["avatar"] in a.keep_all.get(t, {})}
    check(tree["origin"] in origins, "its origin is a segment start of the own avatar", tree["origin"])
    stats = b.stats[0]
    snap_tick = tree_seen_ticks[-1]  # the newest snapshot when the summary came
    check(abs(tree["tick"] - stats["tick"]) <= 3 * 30, "TreeSummary.tick counts server ticks like ServerStats.tick",
          (tree["tick"], stats["tick"]))
    check(tree["tick"] > snap_tick * 1.2, "not snapshots (30 ticks for 20 snapshots a second)",
          (tree["tick"], snap_tick))
    check(stats["players"] == 2 and stats["tick_hz"] == 30, "ServerStats: 2 players at 30 Hz", stats)

    section("bad datagrams are dropped, the session goes on")
    a.dir = (0, 0)
    h.pump(0.2)
    m0 = server.metrics()
    sealed = a.seal(fc.make_session_only(fc.STATS_REQUEST, a.session))
    bad = bytearray(sealed)
    # The payload's last byte is the tag's: the last vector in the buffer (sealed last).
    s_table = fc.table_of(fc.read_packet(sealed), "Sealed")
    vec = s_table._tab.Vector(s_table._tab.Offset(8))
    last = vec + s_table._tab.VectorLen(s_table._tab.Offset(8)) - 1
    bad[last] ^= 0x01
    a.send_raw(bytes(bad))                                                        # a flipped tag bit
    forged = a.seal(fc.make_session_only(fc.STATS_REQUEST, a.session))
    fs = fc.table_of(fc.read_packet(forged), "Sealed")
    forged_session = fc.make_sealed(a.session + 1000, fs.Sequence(), fc.vector_bytes(fs, 2))
    a.send_raw(forged_session)                                                    # another session id
    a.send_raw(fc.make_session_only(fc.STATS_REQUEST, a.session))                 # in the clear
    a.send_raw(a.sent_raw[-1])                                                    # a replay
    stranger = fc.Client(server.address, "stranger")
    stranger.send_raw(sealed)                                                     # from another address
    stranger.close()
    a.send_raw(bytes(sealed[:4]) + b"XXXX" + bytes(sealed[8:]))                   # bad identifier
    a.stats.clear()
    a.request(fc.STATS_REQUEST)
    h.until(lambda: a.stats, 2, "ServerStats after the bad datagrams")
    h.pump(0.2)
    m1 = server.metrics()
    expect = {"unauthenticated": 3, "replayed": 1, "unexpected": 1, "bad_identifier": 1}
    got = {r: drop_metric(m1, r) - drop_metric(m0, r) for r in expect}
    check(got == expect, "each dropped and counted by its reason", got)
    check(len(a.stats) == 1, "exactly one ServerStats: only the genuine request was answered", len(a.stats))
    check(a.stats[0]["packets_dropped"] >= sum(expect.values()), "ServerStats.packets_dropped counts them",
          a.stats[0]["packets_dropped"])
    n = len(a.whole_order)
    h.pump(0.3)
    check(len(a.whole_order) > n and not a.drops, "snapshots keep coming", len(a.whole_order) - n)

    section("clean disconnect")
    gone = acc["avatar"]
    m1 = server.metrics()
    a.disconnect()  # three times
    h.clients.remove(a)
    h.pump(0.3)
    b.stats.clear()
    b.request(fc.STATS_REQUEST)
    h.until(lambda: b.stats, 2, "ServerStats after the disconnect")
    m2 = server.metrics()
    check(b.stats[0]["players"] == 1, "ServerStats: 1 player", b.stats[0]["players"])
    check(m2["foresight_sessions_closed_total"] == 1 and m2["foresight_sessions_timed_out_total"] == 0,
          "metrics: 1 session closed, none timed out",
          (m2["foresight_sessions_closed_total"], m2["foresight_sessions_timed_out_total"]))
    check(f"player {gone} left" in server.log_text(), f"the log says player {gone} left")
    check(drop_metric(m2, "unexpected") - drop_metric(m1, "unexpected") == 2,
          "the Disconnect's two repeats, from an address no longer in session, count as unexpected",
          drop_metric(m2, "unexpected") - drop_metric(m1, "unexpected"))
    n = len(b.whole_order)
    h.pump(0.3)
    check(len(b.whole_order) > n and gone not in b.keep_all[b.whole_order[-1]],
          "the other client's snapshots go on, without that avatar")
    check(server.proc.poll() is None, "the server keeps running")
    b.disconnect()
    a.close()
    b.close()


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--server", required=True)
    ap.add_argument("--schema", required=True)
    ap.add_argument("--generated", help="folder flatc --python wrote into at build time")
    ap.add_argument("--flatc", default="flatc")
    args = ap.parse_args()
    t0 = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="foresight-conformance-") as tmp:
        fc.use_generated(generated_folder(args, tmp))
        print(f"conformance: protocol version {fc.PROTOCOL_VERSION}, 'snapshots back' "
              f"{fc.REF_BACK_BITS} bits, history {fc.HISTORY_SNAPSHOTS}", flush=True)
        try:
            check_document_vectors()
        except Exception as e:  # noqa: BLE001 - a vector that does not even decode
            import traceback
            traceback.print_exc()
            check(False, f"the document's vectors decode ({type(e).__name__}: {e})")
        if not os.access(args.server, os.X_OK):
            check(False, f"server binary {args.server} (build foresight-server)")
        else:
            server = Server(args.server, tmp)
            try:
                server.wait_ready()
                run(server)
            except Exception as e:  # noqa: BLE001 - reported as a failure with the log
                import traceback
                traceback.print_exc()
                check(False, f"ran to the end ({type(e).__name__}: {e})")
            finally:
                server.stop()
                if failures:
                    print("\n-- server log --\n" + server.log_text()[-4000:])
    print(f"\nconformance: {len(failures)} failed, {time.monotonic() - t0:.1f} s", flush=True)
    for f in failures:
        print(f"  FAILED: {f}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())

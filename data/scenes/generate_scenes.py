#!/usr/bin/env python3
"""Writes the built-in scenes (maze, obstacles, terrain, arena, field, doorways, beams, pillars,
dead_end) into this folder.

The JSON files are the source of truth that the game loads; this script is how they were made and
how to remake them after a layout change:  python3 data/scenes/generate_scenes.py
Layouts are documented in docs/SCENES.md. Mazes are drawn as ASCII below: +X to the right, +Z
down, one character cell = one 2.5 m maze cell; '|' and '--' are walls.
"""
import json
import math
import os
from collections import deque

HERE = os.path.dirname(os.path.abspath(__file__))

PITCH = 2.5        # maze cell size, metres
WALL_T = 0.4       # wall thickness -> corridors 2.1 m wide
WALL_H = 2.5       # wall height

MAZE = """
+--+--+--+--+--+--+--+--+
|        |        |     |
+--+--+  +  +--+  +  +  +
|     |     |     |  |  |
+  +  +--+--+  +--+  +  +
|  |        |        |  |
+  +--+--+  +--+--+--+  +
|  |     |              |
+  +  +  +--+--+--+  +--+
|     |     |     |     |
+--+--+--+  +  +  +--+  +
|           |  |     |  |
+  +--+  +  +  +--+  +  +
|  |     |     |  |     |
+  +  +--+--+--+  +--+--+
|  |                    |
+--+--+--+--+--+--+--+--+
"""

OBSTACLE_MAZE = """
+--+--+--+--+--+--+--+--+
|                 |     |
+  +--+--+--+--+  +  +  +
|  |              |  |  |
+  +  +--+  +  +--+  +  +
|  |  |     |  |     |  |
+  +  +  +--+  +  +--+  +
|  |  |     |           |
+  +  +--+  +--+--+  +--+
|  |     |  |        |  |
+  +--+  +  +        +  +
|     |     |        |  |
+  +  +--+--+--+--+  +  +
|  |                    |
+  +--+--+--+--+--+--+  +
|                       |
+--+--+--+--+--+--+--+--+
"""


def parse_maze(text):
    """Returns (rows, cols, hwalls, vwalls): hwalls[(r, c)] = wall on line z = r * PITCH between
    x = c and c + 1 cells; vwalls[(r, c)] = wall on line x = c * PITCH spanning cell row r."""
    lines = [l for l in text.strip("\n").split("\n")]
    rows = (len(lines) - 1) // 2
    cols = (len(lines[0]) - 1) // 3
    hwalls, vwalls = set(), set()
    for li, line in enumerate(lines):
        assert len(line) == 3 * cols + 1, f"line {li} has length {len(line)}"
        if li % 2 == 0:
            r = li // 2
            for c in range(cols):
                seg = line[3 * c + 1:3 * c + 3]
                assert seg in ("--", "  "), f"line {li} col {c}: {seg!r}"
                if seg == "--":
                    hwalls.add((r, c))
        else:
            r = li // 2
            for c in range(cols + 1):
                ch = line[3 * c]
                assert ch in "| ", f"line {li} col {c}: {ch!r}"
                if ch == "|":
                    vwalls.add((r, c))
    return rows, cols, hwalls, vwalls


def maze_neighbours(rows, cols, hwalls, vwalls, r, c):
    if c + 1 < cols and (r, c + 1) not in vwalls:
        yield r, c + 1
    if c > 0 and (r, c) not in vwalls:
        yield r, c - 1
    if r + 1 < rows and (r + 1, c) not in hwalls:
        yield r + 1, c
    if r > 0 and (r, c) not in hwalls:
        yield r - 1, c


def maze_report(name, maze, start, blocked=frozenset()):
    """Checks every cell is reachable; prints dead ends and the walking distance map."""
    rows, cols, hw, vw = maze

    def bfs(skip):
        dist = {start: 0}
        q = deque([start])
        while q:
            cur = q.popleft()
            for n in maze_neighbours(rows, cols, hw, vw, *cur):
                if n in dist or frozenset((cur, n)) in skip:
                    continue
                dist[n] = dist[cur] + 1
                q.append(n)
        return dist

    dist = bfs(frozenset())
    assert len(dist) == rows * cols, f"{name}: unreachable cells"
    dead = [cell for cell in dist if len(list(maze_neighbours(rows, cols, hw, vw, *cell))) == 1]
    walk = bfs(blocked)
    print(f"{name}: {rows}x{cols} cells, {len(dead)} dead ends, "
          f"{len(walk)} cells reachable walking only")
    return dist, walk


def wall_boxes(maze, prefix):
    """Merges collinear wall segments into long boxes."""
    rows, cols, hw, vw = maze
    h = WALL_T / 2
    boxes = []
    for r in range(rows + 1):
        c = 0
        while c < cols:
            if (r, c) in hw:
                c0 = c
                while c < cols and (r, c) in hw:
                    c += 1
                boxes.append(box("wall", f"{prefix}h{r}-{c0}",
                                 [c0 * PITCH - h, 0.0, r * PITCH - h],
                                 [c * PITCH + h, WALL_H, r * PITCH + h]))
            else:
                c += 1
    for c in range(cols + 1):
        r = 0
        while r < rows:
            if (r, c) in vw:
                r0 = r
                while r < rows and (r, c) in vw:
                    r += 1
                boxes.append(box("wall", f"{prefix}v{c}-{r0}",
                                 [c * PITCH - h, 0.0, r0 * PITCH - h],
                                 [c * PITCH + h, WALL_H, r * PITCH + h]))
            else:
                r += 1
    return boxes


def cell_centre(r, c):
    return [c * PITCH + PITCH / 2, r * PITCH + PITCH / 2]


def r3(v):
    return [round(x, 3) for x in v]


def box(kind, name, lo, hi):
    return {"kind": kind, "name": name, "min": r3(lo), "max": r3(hi)}


def low_walls(inner, height, t=0.3):
    """Four walls of thickness t just outside the square [-inner, inner]^2 (arena, field)."""
    o = inner + t
    return [
        box("wall", "low-wall-west", [-o, 0, -o], [-inner, height, o]),
        box("wall", "low-wall-east", [inner, 0, -o], [o, height, o]),
        box("wall", "low-wall-south", [-inner, 0, -o], [inner, height, -inner]),
        box("wall", "low-wall-north", [-inner, 0, inner], [inner, height, o]),
    ]


def camera(name, corner, centre, region_min, region_max, height=9.0, fov=60.0):
    return {"name": name, "position": r3([corner[0], height, corner[1]]),
            "target": r3([centre[0], 0.0, centre[1]]), "fov_y_deg": fov,
            "region": {"min": r3(region_min), "max": r3(region_max)}}


def quadrant_cameras(lo, hi, overlap=1.0, height=9.0):
    """Four cameras, each covering a quadrant (plus overlap), placed above the outer corner."""
    mid = [(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2]
    cams = []
    names = {(0, 0): "cam-nw", (1, 0): "cam-ne", (0, 1): "cam-sw", (1, 1): "cam-se"}
    for qx in (0, 1):
        for qz in (0, 1):
            rmin = [lo[0] if qx == 0 else mid[0] - overlap, lo[1] if qz == 0 else mid[1] - overlap]
            rmax = [mid[0] + overlap if qx == 0 else hi[0], mid[1] + overlap if qz == 0 else hi[1]]
            corner = [lo[0] - 2 if qx == 0 else hi[0] + 2, lo[1] - 2 if qz == 0 else hi[1] + 2]
            centre = [(rmin[0] + rmax[0]) / 2, (rmin[1] + rmax[1]) / 2]
            cams.append(camera(names[(qx, qz)], corner, centre, rmin, rmax, height))
    return cams


def write_scene(filename, scene):
    """One box / point per line, heights one row per line: diff-friendly and readable."""
    out = ["{"]
    keys = list(scene.keys())
    for i, key in enumerate(keys):
        value = scene[key]
        comma = "," if i + 1 < len(keys) else ""
        if isinstance(value, list):
            if not value:
                out.append(f'  "{key}": []{comma}')
                continue
            out.append(f'  "{key}": [')
            for j, item in enumerate(value):
                out.append("    " + json.dumps(item) + ("," if j + 1 < len(value) else ""))
            out.append(f"  ]{comma}")
        elif key == "terrain":
            out.append('  "terrain": {')
            tkeys = list(value.keys())
            for ti, tk in enumerate(tkeys):
                tcomma = "," if ti + 1 < len(tkeys) else ""
                tv = value[tk]
                if tk == "height_field":
                    nx, nz = tv["count"]
                    out.append('    "height_field": {')
                    out.append(f'      "origin": {json.dumps(tv["origin"])}, "cell": {tv["cell"]},'
                               f' "count": [{nx}, {nz}],')
                    out.append('      "heights": [')
                    hs = tv["heights"]
                    for row in range(nz):
                        vals = ",".join("null" if h is None else f"{h:g}"
                                        for h in hs[row * nx:(row + 1) * nx])
                        out.append("        " + vals + ("," if row + 1 < nz else ""))
                    out.append("      ]")
                    out.append("    }" + tcomma)
                elif isinstance(tv, list):
                    out.append(f'    "{tk}": [')
                    for j, item in enumerate(tv):
                        out.append("      " + json.dumps(item) + ("," if j + 1 < len(tv) else ""))
                    out.append(f"    ]{tcomma}")
                else:
                    out.append(f'    "{tk}": {json.dumps(tv)}{tcomma}')
            out.append("  }" + comma)
        else:
            out.append(f'  "{key}": {json.dumps(value)}{comma}')
    out.append("}")
    text = "\n".join(out) + "\n"
    json.loads(text)  # Round-trip check.
    with open(os.path.join(HERE, filename), "w") as f:
        f.write(text)
    print(f"wrote {filename}: {len(text)} bytes")


def maze_scene():
    maze = parse_maze(MAZE)
    start, goal = (0, 0), (6, 7)
    dist, _ = maze_report("maze", maze, start)
    print(f"  goal {goal} is {dist[goal]} cells from start")
    lo, hi = [-0.2, -0.2], [20.2, 20.2]
    return {
        "format": "foresight-scene", "version": 1,
        "name": "maze",
        "_comment": "Maze like Fig. 8 of the feasible-motion-tree paper: 8x8 cells of 2.5 m, "
                    "corridors 2.1 m, walls 2.5 m. Drawn in data/scenes/generate_scenes.py.",
        "bounds": {"min": lo, "max": hi},
        "boxes": wall_boxes(maze, "wall-"),
        "spawns": [{"name": "start", "pos": cell_centre(*start), "heading_deg": 90.0},
                   {"name": "centre", "pos": cell_centre(3, 4), "heading_deg": 90.0}],
        "goals": [{"name": "goal", "pos": cell_centre(*goal), "radius": 0.75},
                  {"name": "dead-end-sw", "pos": cell_centre(7, 0), "radius": 0.75}],
        "cameras": quadrant_cameras(lo, hi),
    }


def obstacles_scene():
    maze = parse_maze(OBSTACLE_MAZE)
    start, goal = (0, 0), (1, 6)
    # Cell edges a walking (not crouching) avatar cannot cross: the beam and the table.
    blocked = frozenset([frozenset(((0, 1), (0, 2))), frozenset(((6, 3), (6, 4)))])
    dist, walk = maze_report("obstacles", maze, start, blocked)
    assert goal in walk, "goal must stay reachable walking, the long way round"
    print(f"  goal {goal}: {dist[goal]} cells from start")
    lo, hi = [-0.2, -0.2], [20.2, 20.2]
    face = WALL_T / 2
    boxes = wall_boxes(maze, "wall-")
    # (a) A beam across the first corridor, bottom 1.25 m: crouch under it (Fig. 11a).
    boxes.append(box("beam", "beam-crouch", [5.0 - 0.15, 1.25, 0.0], [5.0 + 0.15, 1.55, 2.5]))
    # (c) A table across the long south corridor: top 1.3 m, bottom 1.2 m, 1.5 m wide leaving
    # 0.3 m each side (too narrow for a body), so only crouching passes (Fig. 11c).
    boxes.append(box("table", "table", [10.0 - 0.6, 1.2, 15.0 + face + 0.3],
                     [10.0 + 0.6, 1.3, 17.5 - face - 0.3]))
    # (b) In the 3x2 room, a low barrier (bottom 0.6 m: too low to crouch under) spanning most
    # of the room's width: turn around its open end (Fig. 11b).
    boxes.append(box("obstacle", "low-barrier", [12.5 - 0.15, 0.6, 10.0 + face],
                     [12.5 + 0.15, 1.0, 13.6]))
    # A crate on the floor of the room's far half.
    boxes.append(box("obstacle", "crate", [15.6, 0.0, 10.6], [16.4, 0.8, 11.4]))
    return {
        "format": "foresight-scene", "version": 1,
        "name": "obstacles",
        "_comment": "Maze with obstacles like Fig. 11: a beam to crouch under, a table to crouch "
                    "under, a low barrier to turn around. The goal is also reachable walking, "
                    "the long way round.",
        "bounds": {"min": lo, "max": hi},
        "boxes": boxes,
        "spawns": [{"name": "start", "pos": cell_centre(*start), "heading_deg": 90.0}],
        "goals": [{"name": "goal", "pos": cell_centre(*goal), "radius": 0.75},
                  {"name": "far-corner", "pos": cell_centre(7, 7), "radius": 0.75},
                  {"name": "past-beam", "pos": cell_centre(0, 3), "radius": 0.75},
                  {"name": "room", "pos": cell_centre(5, 6), "radius": 0.75}],
        "cameras": quadrant_cameras(lo, hi),
    }


def terrain_heights(nx, nz, cell):
    hs = []
    for iz in range(nz):
        zc = (iz + 0.5) * cell
        for ix in range(nx):
            xc = (ix + 0.5) * cell
            if ix < 40:  # x < 4: level ground
                h = 0.0
            elif ix < 120:  # 4 <= x < 12: gentle rolling slopes (max gradient ~0.12)
                h = 0.15 * math.sin(math.pi * zc / 10.0) * math.sin(2 * math.pi * (xc - 4.0) / 8.0)
            elif ix < 138:  # 12 <= x < 13.8: level strip before the gap
                h = 0.0
            elif ix < 143:  # 13.8 <= x < 14.3: the gap, 0.5 m wide
                h = None
            else:  # a hill, too steep on its flanks for flat clips
                h = 0.6 * math.exp(-((xc - 17.2) ** 2 + (zc - 5.0) ** 2) / (2 * 1.2 ** 2))
            hs.append(None if h is None else round(h, 3) + 0.0)
    return hs


def terrain_scene():
    lo, hi = [0.0, 0.0], [20.0, 20.0]
    t = 0.3
    boxes = [
        box("wall", "wall-west", [0, 0, 0], [t, WALL_H, 20]),
        box("wall", "wall-east", [20 - t, 0, 0], [20, WALL_H, 20]),
        box("wall", "wall-south", [0, 0, 0], [20, WALL_H, t]),
        box("wall", "wall-north", [0, 0, 20 - t], [20, WALL_H, 20]),
        # The divider between the north-west yard and the east room, with a low doorway.
        box("wall", "divider-south", [13.8, 0, 9.8], [14.2, WALL_H, 14.4]),
        box("wall", "divider-north", [13.8, 0, 15.6], [14.2, WALL_H, 20 - t]),
        box("doorway-lintel", "low-doorway", [13.8, 1.4, 14.4], [14.2, WALL_H, 15.6]),
        # Objects at arm height.
        box("shelf", "shelf", [15.5, 1.1, 19.1], [20 - t, 1.3, 20 - t]),
        box("prop", "fuse-box", [14.2, 1.0, 11.0], [14.5, 1.5, 11.6]),
        box("obstacle", "crate", [8.0, 0.0, 12.5], [9.0, 0.8, 13.5]),
    ]
    nx, nz, cell = 200, 100, 0.1
    return {
        "format": "foresight-scene", "version": 1,
        "name": "terrain",
        "_comment": "Uneven ground like the decoupled-footstep paper: rolling slopes, a hill, a "
                    "0.5 m gap (null heights), a 0.18 m step and a second one on it, a low "
                    "doorway (lintel at 1.4 m) and a shelf at 1.1-1.3 m.",
        "bounds": {"min": lo, "max": hi},
        "boxes": boxes,
        "terrain": {
            "floor_y": 0.0,
            "height_field": {"origin": [0.0, 0.0], "cell": cell, "count": [nx, nz],
                             "heights": terrain_heights(nx, nz, cell)},
            "steps": [
                {"name": "step-low", "min": [2.0, 0.0, 12.0], "max": [6.0, 0.18, 18.0]},
                {"name": "step-high", "min": [3.0, 0.18, 13.5], "max": [5.0, 0.36, 16.5]},
            ],
        },
        "spawns": [{"name": "start", "pos": [1.5, 11.0], "heading_deg": 90.0},
                   {"name": "south", "pos": [1.5, 5.0], "heading_deg": 90.0}],
        "goals": [{"name": "east-room", "pos": [17.5, 15.0], "radius": 0.75},
                  {"name": "hilltop", "pos": [17.2, 5.0], "radius": 0.75},
                  {"name": "stairs-top", "pos": [4.0, 15.0], "radius": 0.5}],
        "cameras": quadrant_cameras(lo, hi),
        "npcs": [{"name": "doorkeeper", "kind": "guard", "pos": [17.0, 12.0],
                  "heading_deg": -90.0}],
    }


def arena_scene():
    lo, hi = [-8.3, -8.3], [8.3, 8.3]
    t, wall_h = 0.3, 1.0
    boxes = low_walls(8.0, wall_h, t) + [
        box("obstacle", "pillar-sw", [-4.3, 0, -4.3], [-3.7, 3.0, -3.7]),
        box("obstacle", "pillar-ne", [3.7, 0, 3.7], [4.3, 3.0, 4.3]),
    ]
    return {
        "format": "foresight-scene", "version": 1,
        "name": "arena",
        "_comment": "Open 16x16 m floor inside 1 m walls, two pillars, NPC spawns.",
        "bounds": {"min": lo, "max": hi},
        "boxes": boxes,
        "spawns": [{"name": "player-1", "pos": [-3.0, 0.0], "heading_deg": 90.0},
                   {"name": "player-2", "pos": [3.0, 0.0], "heading_deg": -90.0}],
        "goals": [{"name": "centre", "pos": [0.0, 0.0], "radius": 1.0},
                  {"name": "corner-nw", "pos": [-6.5, -6.5], "radius": 0.75},
                  {"name": "corner-se", "pos": [6.5, 6.5], "radius": 0.75}],
        "cameras": quadrant_cameras(lo, hi, height=7.0),
        "npcs": [{"name": "sparring-partner", "kind": "sparring-partner", "pos": [0.0, 3.0],
                  "heading_deg": 180.0},
                 {"name": "guard-1", "kind": "guard", "pos": [-6.0, 6.0], "heading_deg": 135.0},
                 {"name": "guard-2", "kind": "guard", "pos": [6.0, -6.0], "heading_deg": -45.0},
                 {"name": "wanderer-1", "kind": "wanderer", "pos": [0.0, -5.0], "heading_deg": 0.0},
                 {"name": "wanderer-2", "kind": "wanderer", "pos": [6.0, 2.0],
                  "heading_deg": -135.0}],
    }


def field_scene():
    """A 64 x 64 m open field for load tests (1000 avatars stand in it), a few pillars."""
    lo, hi = [-32.3, -32.3], [32.3, 32.3]
    h = 1.0
    boxes = low_walls(32.0, h)
    for i, (x, z) in enumerate([(-16, -16), (16, -16), (-16, 16), (16, 16), (0, 18), (0, -18)]):
        boxes.append(box("obstacle", f"pillar-{i + 1}", [x - 0.5, 0, z - 0.5], [x + 0.5, 3.0, z + 0.5]))
    spawns = [{"name": f"spawn-{r}-{c}", "pos": [-24.0 + 12.0 * c, -24.0 + 12.0 * r], "heading_deg": 0.0}
              for r in range(5) for c in range(5)]
    goals = [{"name": f"goal-{i + 1}", "pos": list(p), "radius": 1.0}
             for i, p in enumerate([(-28, -28), (28, -28), (-28, 28), (28, 28), (0, 0), (0, 28), (0, -28)])]
    return {
        "format": "foresight-scene", "version": 1,
        "name": "field",
        "_comment": "Open 64x64 m field inside 1 m walls, six pillars, 25 spawns on a 12 m grid: load tests.",
        "bounds": {"min": lo, "max": hi},
        "boxes": boxes,
        "spawns": spawns,
        "goals": goals,
        "cameras": quadrant_cameras(lo, hi, height=20.0),
        "npcs": [],
    }


# ---- Scenes of the size real levels use (issue 17): passages a person fits through -------------
# Passage centres lie on multiples of 0.25 m (the route planner's grid, scene_path.hpp), as a
# level designer's 0.5 m grid would put them.

def outer_walls(w, l, t=0.2, h=WALL_H):
    """Four walls of thickness t along the inside of the bounds [0, w] x [0, l]."""
    return [
        box("wall", "outer-west", [0, 0, 0], [t, h, l]),
        box("wall", "outer-east", [w - t, 0, 0], [w, h, l]),
        box("wall", "outer-south", [t, 0, 0], [w - t, h, t]),
        box("wall", "outer-north", [t, 0, l - t], [w - t, h, l]),
    ]


def small_scene(name, comment, w, l, boxes, spawn, goal, back):
    lo, hi = [0.0, 0.0], [w, l]
    return {
        "format": "foresight-scene", "version": 1,
        "name": name,
        "_comment": comment,
        "bounds": {"min": lo, "max": hi},
        "boxes": outer_walls(w, l) + boxes,
        "spawns": [{"name": "start", "pos": spawn, "heading_deg": 0.0}],
        "goals": [{"name": "goal", "pos": goal, "radius": 0.6},
                  {"name": "back", "pos": back, "radius": 0.6}],
        "cameras": quadrant_cameras(lo, hi, height=8.0),
        "npcs": [],
    }


def doorways_scene():
    """Three cross walls with 0.9 m doorways, offset left, right, left: a standard door's width."""
    boxes = []
    for i, (z, door_x) in enumerate([(3.0, 1.5), (6.0, 4.5), (9.0, 1.5)]):
        lo_z, hi_z = z - 0.1, z + 0.1
        boxes.append(box("wall", f"cross-{i + 1}-a", [0.2, 0, lo_z], [door_x - 0.45, WALL_H, hi_z]))
        boxes.append(box("wall", f"cross-{i + 1}-b", [door_x + 0.45, 0, lo_z], [5.8, WALL_H, hi_z]))
    return small_scene("doorways", "Rooms joined by 0.9 m doorways, offset so every door needs a turn.",
                       6.0, 12.0, boxes, [3.0, 1.25], [3.0, 10.75], [3.0, 1.5])


def beams_scene():
    """A 1.0 m corridor, 6 m long, crossed by beams whose underside is 1.2 m above the floor."""
    boxes = [box("wall", "corridor-west", [0.2, 0, 4.0], [2.5, WALL_H, 10.0]),
             box("wall", "corridor-east", [3.5, 0, 4.0], [5.8, WALL_H, 10.0])]
    for i, z in enumerate([5.5, 7.0, 8.5]):
        boxes.append(box("beam", f"beam-{i + 1}", [2.5, 1.2, z - 0.15], [3.5, 1.5, z + 0.15]))
    return small_scene("beams", "A 1.0 m corridor under three beams at 1.2 m: crouch-walk through it.",
                       6.0, 14.0, boxes, [3.0, 1.5], [3.0, 12.5], [3.0, 1.75])


def pillars_scene():
    """Pillars 0.45 m square on a 1.25 m grid: 0.8 m gaps between them, four rows deep."""
    boxes = []
    for r, zc in enumerate([3.125, 4.375, 5.625, 6.875]):
        for c in range(8):
            xc = 0.625 + 1.25 * c
            boxes.append(box("obstacle", f"pillar-{r + 1}-{c + 1}", [xc - 0.225, 0, zc - 0.225],
                             [xc + 0.225, WALL_H, zc + 0.225]))
    return small_scene("pillars", "A field of pillars with 0.8 m gaps between them, crossed on the diagonal.",
                       10.0, 10.0, boxes, [2.5, 1.25], [7.5, 8.75], [2.5, 1.5])


def dead_end_scene():
    """A U-shaped pocket 4 m deep opening toward the start, the goal right behind it."""
    boxes = [box("wall", "pocket-back", [3.0, 0, 7.8], [9.0, WALL_H, 8.0]),
             box("wall", "pocket-west", [3.0, 0, 4.0], [3.2, WALL_H, 7.8]),
             box("wall", "pocket-east", [8.8, 0, 4.0], [9.0, WALL_H, 7.8])]
    return small_scene("dead_end", "A dead end straight ahead of the start; the goal is behind it.",
                       12.0, 12.0, boxes, [6.0, 1.5], [6.0, 10.5], [6.0, 1.75])


if __name__ == "__main__":
    write_scene("maze.json", maze_scene())
    write_scene("obstacles.json", obstacles_scene())
    write_scene("terrain.json", terrain_scene())
    write_scene("arena.json", arena_scene())
    write_scene("field.json", field_scene())
    write_scene("doorways.json", doorways_scene())
    write_scene("beams.json", beams_scene())
    write_scene("pillars.json", pillars_scene())
    write_scene("dead_end.json", dead_end_scene())

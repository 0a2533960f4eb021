#!/usr/bin/env python3
"""Independent readers and checks of clmesh's -v, -o2, -g, --vtk and -r files.

Used by triangle_files.sh; each command prints one line per problem and exits
1 when there is any.

  voronoi BASE [REFERENCE_BASE]  BASE.v.node and BASE.v.edge against the mesh
      BASE.node / BASE.ele: one circumcentre per triangle (equidistant from its
      corners), one Voronoi edge per mesh edge (finite ones perpendicular to
      the shared mesh edge, rays the outward normals of hull edges); with a
      reference (Triangle's BASE.v.*), the same counts and the same rays.
  o2 BASE [REFERENCE_BASE]  six-node triangles: every middle node is (a + b) / 2
      of its edge's corners, shared by both triangles of the edge; with a
      reference, the same nodes (coordinates, attributes, markers).
  off BASE  BASE.off holds BASE.node's points and BASE.ele's corners.
  vtu FILE BASE  the .vtu holds BASE.node's points, markers and attributes and
      BASE.ele's triangles (quadratic with six nodes) and attributes.
  refined BASE INPUT [MAX_AREA]  BASE refines the mesh INPUT (-r): INPUT's
      vertices come first, with their numbers and coordinates; the domain has
      INPUT's area; each triangle's attributes are those of an INPUT triangle;
      with MAX_AREA no triangle is larger; with INPUT.area, no triangle is
      larger than the bound of the INPUT triangle holding its centroid (of one
      of them, when it lies on their edge).
  boundary BASE  BASE.poly's segments are exactly the boundary edges of
      BASE.ele (-rc without -p).
"""
import math
import sys
import xml.etree.ElementTree as ET

problems = []


def problem(text):
    problems.append(text)


def rows(path):
    """The data lines of a Triangle file, comments removed, as word lists."""
    with open(path) as f:
        for line in f:
            words = line.split("#", 1)[0].split()
            if words:
                yield words


def read_node(path):
    """{number: (x, y, [attributes], marker or None)}, and the first number."""
    lines = list(rows(path))
    count, _, attributes, markers = (int(w) for w in lines[0][:4])
    nodes = {}
    for words in lines[1 : 1 + count]:
        values = [float(w) for w in words[1 : 3 + attributes]]
        marker = int(words[3 + attributes]) if markers else None
        nodes[int(words[0])] = (values[0], values[1], values[2:], marker)
    if len(nodes) != count:
        problem(f"{path}: {len(nodes)} nodes, header says {count}")
    return nodes, attributes, markers


def read_ele(path):
    lines = list(rows(path))
    count, corners, attributes = (int(w) for w in lines[0][:3])
    triangles = []
    for words in lines[1 : 1 + count]:
        triangles.append(
            ([int(w) for w in words[1 : 1 + corners]],
             [float(w) for w in words[1 + corners : 1 + corners + attributes]]))
    if len(triangles) != count:
        problem(f"{path}: {len(triangles)} triangles, header says {count}")
    return triangles, corners, attributes


def read_voronoi(base):
    vnodes, _, _ = read_node(base + ".v.node")
    lines = list(rows(base + ".v.edge"))
    count = int(lines[0][0])
    edges = []
    for words in lines[1 : 1 + count]:
        a, b = int(words[1]), int(words[2])
        direction = (float(words[3]), float(words[4])) if b == -1 else None
        edges.append((a, b, direction))
    return vnodes, edges


def mesh_edges(triangles):
    """{(smaller, larger) corner pair: [(triangle, p, q)]}, p -> q counter-clockwise."""
    edges = {}
    for t, (corners, _) in enumerate(triangles):
        for i in range(3):
            p, q = corners[(i + 1) % 3], corners[(i + 2) % 3]
            edges.setdefault((min(p, q), max(p, q)), []).append((t, p, q))
    return edges


def check_voronoi(base, reference):
    nodes, _, _ = read_node(base + ".node")
    triangles, _, _ = read_ele(base + ".ele")
    vnodes, vedges = read_voronoi(base)
    first = min(vnodes) if vnodes else 1
    edges = mesh_edges(triangles)
    if len(vnodes) != len(triangles):
        problem(f"{len(vnodes)} Voronoi vertices for {len(triangles)} triangles")
    if len(vedges) != len(edges):
        problem(f"{len(vedges)} Voronoi edges for {len(edges)} mesh edges")
    for t, (corners, _) in enumerate(triangles):
        cx, cy = vnodes[t + first][:2]
        radii = [math.hypot(cx - nodes[v][0], cy - nodes[v][1]) for v in corners[:3]]
        scale = max(radii) + max(abs(cx), abs(cy))
        if max(radii) - min(radii) > 1e-12 * scale:
            problem(f"Voronoi vertex {t + first} is not equidistant: {radii}")
    # Each mesh edge: the triangles on its sides, by triangle number.
    by_pair = {}
    hull = {}
    for (lo, hi), sides in edges.items():
        if len(sides) == 2:
            by_pair[tuple(sorted((sides[0][0], sides[1][0])))] = (lo, hi)
        else:
            t, p, q = sides[0]
            hull.setdefault(t, []).append((p, q))
    seen = set()
    for a, b, direction in vedges:
        ta = a - first
        if direction is None:
            tb = b - first
            pair = tuple(sorted((ta, tb)))
            if pair not in by_pair or pair in seen:
                problem(f"Voronoi edge {a} {b}: not one pair of neighbouring triangles")
                continue
            seen.add(pair)
            lo, hi = by_pair[pair]
            ex, ey = nodes[hi][0] - nodes[lo][0], nodes[hi][1] - nodes[lo][1]
            (ax, ay), (bx, by) = vnodes[a][:2], vnodes[b][:2]
            dot = (bx - ax) * ex + (by - ay) * ey
            if abs(dot) > 1e-12 * math.hypot(ex, ey) * (math.hypot(bx - ax, by - ay) + abs(ax) + abs(ay) + 1):
                problem(f"Voronoi edge {a} {b} is not perpendicular to mesh edge {lo} {hi}")
        else:
            matches = [(p, q) for p, q in hull.get(ta, [])
                       if direction == (nodes[q][1] - nodes[p][1], nodes[p][0] - nodes[q][0])]
            if not matches:
                problem(f"ray from {a} along {direction}: no hull edge of triangle {a} has that normal")
            else:
                hull[ta].remove(matches[0])
    if any(hull.values()):
        problem(f"hull edges without a ray: {[e for e in hull.values() if e]}")
    if reference:
        rnodes, redges = read_voronoi(reference)
        if (len(rnodes), len(redges)) != (len(vnodes), len(vedges)):
            problem(f"{len(vnodes)} vertices and {len(vedges)} edges; Triangle: "
                    f"{len(rnodes)} and {len(redges)}")

        def rays(vn, ve):
            return sorted((d, vn[a][:2]) for a, _, d in ve if d is not None)

        mine, theirs = rays(vnodes, vedges), rays(rnodes, redges)
        if len(mine) != len(theirs):
            problem(f"{len(mine)} rays; Triangle: {len(theirs)}")
        for (d, o), (rd, ro) in zip(mine, theirs):
            if d != rd or math.hypot(o[0] - ro[0], o[1] - ro[1]) > 1e-9 * (1 + math.hypot(*o)):
                problem(f"ray {o} along {d}; Triangle's: {ro} along {rd}")


def check_o2(base, reference):
    nodes, attributes, _ = read_node(base + ".node")
    triangles, corners, _ = read_ele(base + ".ele")
    if corners != 6:
        problem(f"{base}.ele: {corners} nodes per triangle, wanted 6")
        return
    middle_of = {}
    for corners_, _ in triangles:
        for i in range(3):
            p, q, m = corners_[(i + 1) % 3], corners_[(i + 2) % 3], corners_[3 + i]
            want = ((nodes[p][0] + nodes[q][0]) * 0.5, (nodes[p][1] + nodes[q][1]) * 0.5)
            if nodes[m][:2] != want:
                problem(f"node {m} is not the midpoint of {p} {q}: {nodes[m][:2]} != {want}")
            key = (min(p, q), max(p, q))
            if middle_of.setdefault(key, m) != m:
                problem(f"edge {key} has two middle nodes, {middle_of[key]} and {m}")
    corner_nodes = {v for c, _ in triangles for v in c[:3]}
    if max(corner_nodes) >= min(middle_of.values()):
        problem("middle nodes are not numbered after the vertices")
    if reference:
        def node_set(n):
            return sorted((x, y, tuple(a), m) for x, y, a, m in n.values())

        rnodes, _, _ = read_node(reference + ".node")
        rtriangles, rcorners, _ = read_ele(reference + ".ele")
        if (len(nodes), len(triangles), corners) != (len(rnodes), len(rtriangles), rcorners):
            problem(f"{len(nodes)} nodes, {len(triangles)} triangles of {corners}; Triangle: "
                    f"{len(rnodes)}, {len(rtriangles)} of {rcorners}")
        elif node_set(nodes) != node_set(rnodes):
            problem("the nodes (coordinates, attributes, markers) differ from Triangle's")


def check_off(base):
    nodes, _, _ = read_node(base + ".node")
    triangles, _, _ = read_ele(base + ".ele")
    with open(base + ".off") as f:
        words = [line.split("#", 1)[0].split() for line in f]
    words = [w for w in words if w]
    if words[0] != ["OFF"]:
        problem(f"{base}.off does not start with OFF")
        return
    vertices, faces, edges = (int(w) for w in words[1])
    first = min(nodes)
    if vertices != len(nodes) or faces != len(triangles) or edges != len(mesh_edges(triangles)):
        problem(f"{base}.off header {words[1]}; wanted {len(nodes)} {len(triangles)} "
                f"{len(mesh_edges(triangles))}")
    for k in range(vertices):
        x, y, z = (float(w) for w in words[2 + k])
        if (x, y, z) != (nodes[k + first][0], nodes[k + first][1], 0.0):
            problem(f"{base}.off vertex {k}: {x} {y} {z}")
    for t in range(faces):
        face = [int(w) for w in words[2 + vertices + t]]
        if face != [3] + [v - first for v in triangles[t][0][:3]]:
            problem(f"{base}.off face {t}: {face}")


def check_vtu(path, base):
    nodes, attributes, markers = read_node(base + ".node")
    triangles, corners, cell_attributes = read_ele(base + ".ele")
    first = min(nodes)
    piece = ET.parse(path).getroot().find("UnstructuredGrid/Piece")
    if int(piece.get("NumberOfPoints")) != len(nodes) or int(piece.get("NumberOfCells")) != len(triangles):
        problem(f"{path}: {piece.get('NumberOfPoints')} points, {piece.get('NumberOfCells')} cells")

    def array(where, name=None):
        for a in piece.find(where).findall("DataArray"):
            if name is None or a.get("Name") == name:
                return a.text.split()
        problem(f"{path}: no {where} array {name}")
        return []

    coordinates = [float(w) for w in array("Points")]
    for k in range(len(nodes)):
        if tuple(coordinates[3 * k : 3 * k + 3]) != (nodes[k + first][0], nodes[k + first][1], 0.0):
            problem(f"{path}: point {k} is {coordinates[3 * k : 3 * k + 3]}")
            break
    connectivity = [int(w) for w in array("Cells", "connectivity")]
    offsets = [int(w) for w in array("Cells", "offsets")]
    types = [int(w) for w in array("Cells", "types")]
    order = [0, 1, 2, 5, 3, 4] if corners == 6 else [0, 1, 2]  # VTK's quadratic triangle
    want = [triangles[t][0][i] - first for t in range(len(triangles)) for i in order]
    if connectivity != want:
        problem(f"{path}: connectivity differs from the .ele")
    if offsets != [len(order) * (t + 1) for t in range(len(triangles))]:
        problem(f"{path}: offsets are wrong")
    if types != [22 if corners == 6 else 5] * len(triangles):
        problem(f"{path}: cell types {set(types)}")
    if markers:
        got = [int(w) for w in array("PointData", "marker")]
        if got != [nodes[k + first][3] for k in range(len(nodes))]:
            problem(f"{path}: markers differ from the .node")
    for a in range(attributes):
        got = [float(w) for w in array("PointData", f"attribute{a + 1}")]
        if got != [nodes[k + first][2][a] for k in range(len(nodes))]:
            problem(f"{path}: attribute{a + 1} differs from the .node")
    for a in range(cell_attributes):
        got = [float(w) for w in array("CellData", f"attribute{a + 1}")]
        if got != [triangles[t][1][a] for t in range(len(triangles))]:
            problem(f"{path}: cell attribute{a + 1} differs from the .ele")


def triangle_area(nodes, corners):
    (ax, ay), (bx, by), (cx, cy) = (nodes[v][:2] for v in corners[:3])
    return 0.5 * ((bx - ax) * (cy - ay) - (by - ay) * (cx - ax))


def check_refined(base, given, max_area):
    nodes, _, _ = read_node(base + ".node")
    triangles, _, _ = read_ele(base + ".ele")
    given_nodes, _, _ = read_node(given + ".node")
    given_triangles, _, _ = read_ele(given + ".ele")
    for number, node in given_nodes.items():
        if nodes.get(number, (None, None))[:2] != node[:2]:
            problem(f"{base}.node: input vertex {number} {node[:2]} is not kept")
            break
    domain = sum(triangle_area(given_nodes, t) for t, _ in given_triangles)
    total = sum(triangle_area(nodes, t) for t, _ in triangles)
    if abs(total - domain) > 1e-9 * domain:
        problem(f"{base}: domain area {total!r}, the input's is {domain!r}")
    given_rows = {tuple(a) for _, a in given_triangles}
    for number, (corners, attributes) in enumerate(triangles):
        if tuple(attributes) not in given_rows:
            problem(f"{base}.ele: triangle {number}'s attributes {attributes} are no input "
                    "triangle's")
            break
    largest = max(triangle_area(nodes, t) for t, _ in triangles)
    if max_area is not None and largest > max_area * (1 + 1e-9):
        problem(f"{base}: a triangle of area {largest!r} exceeds -a{max_area!r}")
    try:
        bounds = [float(w[1]) for w in list(rows(given + ".area"))[1:]]
    except FileNotFoundError:
        return
    given_corners = [[given_nodes[v][:2] for v in t[:3]] for t, _ in given_triangles]
    for number, (corners, _) in enumerate(triangles):
        centroid = tuple(sum(nodes[v][k] for v in corners[:3]) / 3 for k in range(2))
        holders = [i for i, g in enumerate(given_corners) if holds(g, centroid)]
        loosest = max((bounds[i] if bounds[i] > 0 else math.inf for i in holders), default=None)
        if loosest is None:
            problem(f"{base}.ele: triangle {number}'s centroid lies in no input triangle")
            break
        if triangle_area(nodes, corners) > loosest * (1 + 1e-9):
            problem(f"{base}.ele: triangle {number} of area {triangle_area(nodes, corners)!r} "
                    f"exceeds the bound {loosest!r} of the input triangle holding its centroid")
            break


def holds(corners, point):
    """Whether the counter-clockwise triangle `corners` holds `point` (its edges included)."""
    (x, y) = point
    for (ax, ay), (bx, by) in zip(corners, corners[1:] + corners[:1]):
        if (bx - ax) * (y - ay) - (by - ay) * (x - ax) < 0:
            return False
    return True


def check_boundary(base):
    triangles, _, _ = read_ele(base + ".ele")
    count = {}
    for corners, _ in triangles:
        for i in range(3):
            edge = frozenset((corners[i], corners[(i + 1) % 3]))
            count[edge] = count.get(edge, 0) + 1
    boundary = {edge for edge, n in count.items() if n == 1}
    lines = list(rows(base + ".poly"))
    segments = int(lines[1][0])
    listed = {frozenset(int(w) for w in words[1:3]) for words in lines[2 : 2 + segments]}
    if listed != boundary or segments != len(boundary):
        problem(f"{base}.poly: {segments} segments, {len(listed & boundary)} of them among the "
                f"{len(boundary)} boundary edges of {base}.ele")


def main():
    command, args = sys.argv[1], sys.argv[2:]
    if command == "voronoi":
        check_voronoi(args[0], args[1] if len(args) > 1 else None)
    elif command == "o2":
        check_o2(args[0], args[1] if len(args) > 1 else None)
    elif command == "off":
        check_off(args[0])
    elif command == "vtu":
        check_vtu(args[0], args[1])
    elif command == "boundary":
        check_boundary(args[0])
    elif command == "refined":
        check_refined(args[0], args[1], float(args[2]) if len(args) > 2 else None)
    else:
        sys.exit(f"unknown command {command}")
    for text in problems:
        print(f"{command} {' '.join(args)}: {text}")
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()

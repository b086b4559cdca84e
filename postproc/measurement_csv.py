"""A measurement CSV read, for postproc/measurement.py to align (not a script itself).

Format (docs/assessment.md "Measurements"): comma-separated, '#' lines are comments; the
first other line is the header, every column with its unit in brackets. A row is one
instant of the train:
  x [m] (or [km])        contact point position along the track of the pantograph of the
                         first force column, increasing; or
  t [s]                  time, increasing, with the speed given by
  speed [km/h] (or [m/s])  a column: the train's speed at every row, positive
                         (x = v0 t0 + the trapezoid integral of v dt from the first row), or
                         by a comment line '# speed [km/h]: V' (x = V t)
  force [N] (or [kN])    measured contact force of the first pantograph; or, one per
  force NAME [N]         pantograph, the contact force of the run's pantograph NAME
  uplift X [mm] (or [m]) optional, any number: contact-wire uplift at the support at X m
"""
import re

import numpy as np

import pcsim_post

UNITS = {"x": {"m": 1.0, "km": 1000.0}, "t": {"s": 1.0}, "speed": {"km/h": 1 / 3.6, "m/s": 1.0},
         "force": {"N": 1.0, "kN": 1000.0}, "uplift": {"mm": 1e-3, "m": 1.0}}
MIN_ROWS = 64
KNOWN = "x [m], t [s], speed [km/h], force [N], force NAME [N], uplift X [mm]"


class Column:
    """One header column: kind (x, t, speed, force, uplift), name (a force column's pantograph,
    None for 'force [N]'), support_x (an uplift column's support), scale to SI, header text."""

    def __init__(self, path, number, cell):
        self.text, self.number = cell, number
        m = re.fullmatch(r"([^\[\]]*?)\s*(\[([^\]]*)\])?", cell)
        words = m.group(1).split(None, 1) if m else []
        self.kind = words[0] if words else ""
        rest = words[1].strip() if len(words) > 1 else None
        self.name = rest if self.kind == "force" else None
        self.support_x = None
        if self.kind == "uplift" and rest is not None and re.fullmatch(r"-?[0-9.]+", rest):
            self.support_x = float(rest)
        if (self.kind not in UNITS or (rest is not None and self.kind not in ("force", "uplift"))
                or (self.kind == "uplift" and self.support_x is None)):
            pcsim_post.fail("%s: header column %d '%s' is none of %s" % (path, number, cell, KNOWN))
        if m.group(2) is None:
            pcsim_post.fail("%s: header column '%s' has no unit (write e.g. '%s [%s]')"
                            % (path, cell, cell, next(iter(UNITS[self.kind]))))
        unit = m.group(3).strip()
        if unit not in UNITS[self.kind]:
            pcsim_post.fail("%s: header column '%s': unit '%s' is not one of %s"
                            % (path, cell, unit, ", ".join(UNITS[self.kind])))
        self.scale = UNITS[self.kind][unit]

    def key(self):
        return (self.kind, self.name, self.support_x)


def parse_header(path, header):
    """The header's columns, checked: one x or t, a speed column only with t, one force column
    or named ones, no column twice."""
    columns = [Column(path, i + 1, c.strip()) for i, c in enumerate(header.split(","))]
    for i, c in enumerate(columns):
        for earlier in columns[:i]:
            if c.key() == earlier.key() or (c.kind in ("x", "t") and earlier.kind in ("x", "t")):
                pcsim_post.fail("%s: header column %d '%s' repeats column %d '%s' (one of each)"
                                % (path, c.number, c.text, earlier.number, earlier.text))
    kinds = [c.kind for c in columns]
    if "force" not in kinds or kinds.count("x") + kinds.count("t") != 1:
        pcsim_post.fail("%s: the header needs one position column 'x [m]' or time column "
                        "'t [s]' and a force column 'force [N]' (it has: %s)" % (path, header.strip()))
    forces = [c for c in columns if c.kind == "force"]
    unnamed = [c for c in forces if c.name is None]
    if unnamed and len(forces) > 1:
        pcsim_post.fail("%s: header column '%s' (the first pantograph) together with other force "
                        "columns: name every one, 'force NAME [N]'" % (path, unnamed[0].text))
    speed = [c for c in columns if c.kind == "speed"]
    if speed and "x" in kinds:
        pcsim_post.fail("%s: header column '%s' goes with a time column 't [s]', not with a "
                        "position column" % (path, speed[0].text))
    return columns


def speed_comment(comments):
    """(speed in km/h, the comment line) of a comment '# speed [km/h]: V', or (None, None)."""
    for c in comments:
        m = re.match(r"#\s*speed\s*\[km/h\]\s*[:=]\s*([0-9.eE+-]+)\s*$", c.strip())
        if m:
            return float(m.group(1)), c.strip()
    return None, None


class Measurement:
    """A measurement CSV: per row the time (s; None for a position file) and the position of
    the first force column's pantograph (m); forces {pantograph name or None: N}; uplift
    histories at supports (m)."""

    def __init__(self, path):
        self.path = pcsim_post.need_file(path, "measurement")
        with open(path, errors="replace") as f:
            lines = [(n + 1, l) for n, l in enumerate(f) if l.strip()]
        comments = [l for _, l in lines if l.lstrip().startswith("#")]
        data = [(n, l) for n, l in lines if not l.lstrip().startswith("#")]
        if not data:
            pcsim_post.fail("%s: no header line" % path)
        columns = parse_header(path, data[0][1])
        rows = [self.row(n, l, len(columns)) for n, l in data[1:]]
        if len(rows) < MIN_ROWS:
            pcsim_post.fail("%s: %d rows, at least %d needed" % (path, len(rows), MIN_ROWS))
        table = np.array(rows) * np.array([c.scale for c in columns])
        self.line_numbers = [n for n, _ in data[1:]]
        self.axis = "x" if any(c.kind == "x" for c in columns) else "t"
        axis = next(i for i, c in enumerate(columns) if c.kind == self.axis)
        if np.any(np.diff(table[:, axis]) <= 0):
            pcsim_post.fail("%s: column %s does not increase strictly" % (path, columns[axis].text))
        self.speed_kmh, comment = speed_comment(comments)
        self.time, self.speed = None, None
        if self.axis == "t":
            self.time = table[:, axis]
            self.speed = self.speed_of(columns, table, comment)
            self.x = position_from_speed(self.time, self.speed)
        else:
            self.x = table[:, axis]
        self.forces = {c.name: table[:, i] for i, c in enumerate(columns) if c.kind == "force"}
        self.force_columns = {c.name: c.text for c in columns if c.kind == "force"}
        self.support_x = np.array([c.support_x for c in columns if c.kind == "uplift"])
        self.uplift = table[:, [i for i, c in enumerate(columns) if c.kind == "uplift"]]
        self.comments = [c.lstrip("# ").rstrip() for c in comments]

    def row(self, number, line, width):
        cells = line.split(",")
        try:
            values = [float(c) for c in cells]
        except ValueError:
            values = []
        if len(values) != width or not np.all(np.isfinite(values)):
            pcsim_post.fail("%s: line %d: %d numbers expected: %s"
                            % (self.path, number, width, line.strip()[:60]))
        return values

    def speed_of(self, columns, table, comment):
        """The speed at every row (m/s): the speed column's, or the comment's."""
        column = next((i for i, c in enumerate(columns) if c.kind == "speed"), None)
        if column is None:
            if self.speed_kmh is None:
                pcsim_post.fail("%s: a time column needs the speed: a column 'speed [km/h]' or a "
                                "comment line '# speed [km/h]: V'" % self.path)
            if self.speed_kmh <= 0:
                pcsim_post.fail("%s: comment line '%s': the speed must be positive" % (self.path, comment))
            return np.full(len(table), self.speed_kmh / 3.6)
        if comment is not None:
            pcsim_post.fail("%s: the speed is given twice, by column '%s' and by comment line '%s': "
                            "keep one" % (self.path, columns[column].text, comment))
        speed = table[:, column]
        if np.any(speed <= 0):
            k = int(np.argmax(speed <= 0))
            pcsim_post.fail("%s: line %d: column '%s' is %g: the speed must be positive"
                            % (self.path, self.line_numbers[k], columns[column].text,
                               speed[k] / columns[column].scale))
        return speed

    def spacing(self):
        return float(np.median(np.diff(self.x)))


def position_from_speed(time, speed):
    """x = v0 t0 + the trapezoid integral of v dt from the first row: the time origin t = 0 is
    when the contact point was at x = 0, at the first row's speed before it (x = V t for a
    constant speed V)."""
    steps = 0.5 * (speed[1:] + speed[:-1]) * np.diff(time)
    return speed[0] * time[0] + np.concatenate(([0.0], np.cumsum(steps)))

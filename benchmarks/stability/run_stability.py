#!/usr/bin/python3
"""Stability on hard cases (issue 5): run the long version of every case
with each of the five schemes and write doc/stability.md, a table case x
scheme with the largest penetration, the energy change, the active-set
changes per step, whether the case's checks hold, and the documented
behaviour.

usage (from the repository top, after building):
    /usr/bin/python3 benchmarks/stability/run_stability.py [--build build]
        [--out doc] [--cases a,b] [--schemes x,y] [--quick]
    /usr/bin/python3 benchmarks/stability/run_stability.py --write-tests

--quick runs the short versions (the lengths of the tests) instead of the
long ones and prints the table without writing the page. --write-tests
writes the parameter files of tests/stability from the same definitions
(self-contained files, no include); their .output files are made by running
the tests and reading them. Every run of cases ends with
results/stability/summary.json (each run's exit code and message) and one
`RESULT program=run_stability ... runs=... nonzero_exits=...` line.

The cases are variants of one scene, program block_on_plane: an elastic
block 0.1 m x 0.05 m x 0.01 m (E = 1e7 Pa, rho = 1e3 kg/m^3, mass 0.05 kg,
nu = 0.3, plane strain) on the rigid plane y = 0 under gravity. Each case
states its bounds per scheme (the same in the test and in the long run) and
what the scheme is expected to do; a scheme that fails a case by nature is
checked for that behaviour, not given a looser bound.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "common"))
import runs  # noqa: E402

# ---------------------------------------------------------------------------
# The five schemes: key, label, Time stepping entries.
SCHEMES = {
    "theta_05": ("θ-method θ = 0.5", {"Scheme": "theta", "Theta": "0.5"}),
    "theta_055": ("θ-method θ = 0.55", {"Scheme": "theta", "Theta": "0.55"}),
    "theta_euler": ("θ-Euler θ = 0.55", {"Scheme": "theta-euler", "Theta": "0.55"}),
    "modified_theta": ("modified θ θ = 0.55",
                       {"Scheme": "modified-theta", "Theta": "0.55"}),
    "newmark": ("Newmark β = 1/4, γ = 1/2",
                {"Scheme": "newmark", "Newmark beta": "0.25",
                 "Newmark gamma": "0.5"}),
}
THETA = ["theta_05", "theta_055", "theta_euler", "modified_theta"]
DAMPED = ["theta_055", "theta_euler", "modified_theta"]
ALL = THETA + ["newmark"]

# The block every case starts from.
BLOCK = {
    "Geometry": {"Width": "0.1", "Height": "0.05", "Thickness": "0.01",
                 "Number of cells across": "8", "Number of cells up": "4",
                 "Initial gap": "0"},
    "Initial conditions": {"Horizontal velocity": "0", "Vertical velocity": "0"},
    "Loads": {"Gravity": "0, -9.81", "Push force": "0, 0"},
    "Obstacle": {"Type": "plane", "Point on plane": "0, 0", "Normal": "0, 1",
                 "Friction coefficient": "0"},
    "Material": {"Young's modulus": "1e7", "Density": "1e3",
                 "Poisson's ratio": "0.3", "Plane model": "plane strain"},
}

# Round-off of the energy: 1/2 u.Ku is summed from terms of size
# ||K|| |u|^2 that cancel down to the strain energy (u includes the rigid
# motion: a block that slid 1 m, a steel block that flew 1 m), so a step can
# show an increase of about R = eps (||K|| |u|^2 + ||M|| |v|^2 + |F| |u|).
# block_on_plane prints R; a scheme that cannot increase the energy must
# stay within 100 R (observed: up to 4 R; real growth is 1e5 R and more).
NO_GROWTH = dict(increase_roundoff="100", max_energy_ratio="1.000001")


def merge(*parts):
    """Parameter dictionaries {subsection: {entry: value}}, later wins."""
    out = {}
    for part in parts:
        for sub, entries in part.items():
            out.setdefault(sub, {}).update(entries)
    return out


def prm_text(sections, comment="", program="block_on_plane"):
    lines = [f"# program: {program}"]
    lines += [f"# {c}" if c else "#" for c in comment.strip().split("\n")] if comment else []
    for sub, entries in sections.items():
        lines.append(f"subsection {sub}")
        width = max(len(k) for k in entries)
        for k, v in entries.items():
            lines.append(f"  set {k.ljust(width)} = {v}")
        lines.append("end")
    return "\n".join(lines) + "\n"


def checks(**bounds):
    """Verification entries from keyword arguments (bound names below)."""
    names = {
        "penetration": "Maximum penetration",
        "energy_increase": "Maximum energy increase",
        "increase_roundoff": "Maximum energy increase in round-offs",
        "max_energy_ratio": "Maximum energy ratio",
        "min_energy_ratio": "Minimum energy ratio",
        "impulse_balance": "Maximum impulse balance error",
        "coulomb": "Maximum Coulomb excess",
        "final_phase": "Start of the final phase",
        "gap_drift": "Maximum gap drift",
        "final_penetration": "Maximum penetration in the final phase",
        "active_set": "Maximum active-set changes per step",
        "reaction": "Maximum reaction error",
        "stick_time": "Maximum stick time error",
        "distance": "Maximum sliding distance error",
        "final_velocity": "Maximum final velocity error",
        "compression": "Maximum static compression error",
        "min_restitution": "Minimum restitution",
        "max_restitution": "Maximum restitution",
        "err_v": "Maximum err_v",
        "err_f": "Maximum err_f",
    }
    return {"Verification": {names[k]: str(v) for k, v in bounds.items()}}


# At rest in the final phase: no drift, no penetration, no chattering, and
# the plane carries the load.
AT_REST = dict(gap_drift="1e-12", final_penetration="1e-12", active_set="0",
               reaction="1e-6")


class Case:
    """One hard case: scene, short (test) and long (benchmark) lengths,
    bounds and the expected behaviour per scheme, which schemes the test
    suite runs, and which of those print the checks only (their figures
    depend on round-off)."""

    def __init__(self, name, title, scene, short, long, bounds, behaviour,
                 tests, bounds_only=(), short_for=None, program="block_on_plane",
                 figure=None):
        self.name, self.title, self.scene = name, title, scene
        # (column title, function of summary.json) of the case's own figure
        self.figure = figure or ("gap drift [m]", lambda s: fmt(s["stability"]["gap_drift"]))
        self.short, self.long = short, long
        self.bounds, self.behaviour = bounds, behaviour
        self.tests = list(dict.fromkeys(tests))
        self.bounds_only = bounds_only
        # a scheme whose short version must be shorter still (it blows up)
        self.short_for = short_for or {}
        self.program = program

    def sections(self, scheme, length):
        base = BLOCK if self.program == "block_on_plane" else {}
        lengths = (merge(self.short, self.short_for.get(scheme, {}))
                   if length == "short" else self.long)
        return merge(base, self.scene, {"Time stepping": SCHEMES[scheme][1]},
                     lengths, self.bounds.get(scheme, {}))


def time(h, T, final=None):
    d = {"Time stepping": {"Time step": h, "End time": T}}
    if final is not None:
        d["Verification"] = {"Start of the final phase": final}
    return d


CASES = []


def fmt(x, digits=2):
    if x is None:
        return "—"
    if abs(x) < 1e-12:
        return "0" if x == 0 else "< 1e-12"
    return f"{x:.{digits}g}"


RESTITUTION = ("restitution", lambda s: fmt(s["stability"]["restitution"]))
REACTION = ("reaction error, final phase",
            lambda s: fmt(s["stability"]["reaction_error"]))

# --- Time steps far above the Courant limit: the block (nu = 0, so that
# the impact is the one of a bar on a wall: contact 2H/c = 1 ms, leaves at
# v0) falls at 1 m/s; c h / dx = 10 and 100. Each then bounces under
# gravity and comes to rest.
for courant, h, T, pen in [(10, "1.25e-3", "1", "5.7e-4"),
                           (100, "1.25e-2", "2", "5.7e-3")]:
    rest = dict(AT_REST, final_phase=str(float(T) / 2))
    b = {s: checks(penetration="1e-12", **NO_GROWTH, **rest) for s in DAMPED}
    # modified theta: the gap is enforced at u + h(1-theta)v, so a node may
    # sink by up to h (1-theta) v0; giving that back raises the energy in
    # the step after an impact.
    b["modified_theta"] = checks(penetration=pen, max_energy_ratio="1", **rest)
    b["theta_05"] = checks(penetration="1e-12", **NO_GROWTH)
    b["newmark"] = checks(penetration="1e-12", min_restitution="1.5",
                          min_energy_ratio="2")
    CASES.append(Case(
        f"courant_{courant}", f"Courant number {courant}",
        {"Material": {"Poisson's ratio": "0"},
         "Initial conditions": {"Vertical velocity": "-1"}},
        time(h, T), time(h, str(5 * float(T)), str(4 * float(T))),
        b,
        {"theta_05": "no dissipation: restitution of the first impact below 1 "
                     "only because of the elastic vibrations" +
                     ("; keeps chattering on the plane (active set)" if courant == 10 else ""),
         "theta_055": "bounces (θ-method restitution), then rests",
         "theta_euler": "inelastic impact, rests at once",
         "modified_theta": f"penetrates up to h(1-θ)v0 = {pen} m; energy rises "
                           "in the step after the impact; rests",
         "newmark": "fails by nature: leaves faster than it came (restitution "
                    "> 1), the energy grows many times"},
        # Newmark's energy grows by 50 times: its figures carry round-off
        # amplified as much; the checks are robust.
        tests=ALL, bounds_only=(["theta_05"] if courant == 10 else []) + ["newmark"],
        figure=RESTITUTION))

# --- A block resting under gravity for 10^4 steps, with friction (mu =
# 0.5, nu = 0.3: the base wants to spread, the friction holds it).
rest = dict(AT_REST, reaction="1e-4")
CASES.append(Case(
    "rest", "Resting, μ = 0.5, 10⁴ steps",
    {"Obstacle": {"Friction coefficient": "0.5"}},
    time("1e-3", "10"), time("1e-3", "10"),
    {**{s: checks(penetration="1e-12", coulomb="1e-9", **NO_GROWTH, **rest)
        for s in THETA},
     "newmark": checks(penetration="1e-12", coulomb="1e-9",
                       min_energy_ratio="1.2")},
    {"theta_05": "no drift, no chattering; the vertical vibration is kept",
     "theta_055": "no drift, no chattering, vibration damped",
     "theta_euler": "no drift, no chattering, vibration damped",
     "modified_theta": "no drift, no chattering, vibration damped",
     "newmark": "fails by nature: with friction the contact forces pump energy "
                "in (from round-off, after 2 s); the block ends up jumping"},
    tests=THETA, figure=REACTION))

# --- The same without friction and with nu = 0: the top sinks by
# rho g H^2 / (2E) (the column under its own weight, exact at the nodes).
CASES.append(Case(
    "rest_static", "Resting, ν = 0, static compression",
    {"Material": {"Poisson's ratio": "0"},
     "Geometry": {"Number of cells across": "4", "Number of cells up": "2"}},
    time("1e-3", "10"), time("1e-3", "10"),
    {**{s: checks(penetration="1e-12", compression="1e-9", **NO_GROWTH, **AT_REST)
        for s in DAMPED},
     **{s: checks(penetration="1e-12", compression="1e-3", **NO_GROWTH,
                  **dict(AT_REST, reaction="1e-3")) for s in ["theta_05", "newmark"]}},
    {"theta_05": "undamped vibration about the static state (time average exact)",
     "theta_055": "static state to round-off",
     "theta_euler": "static state to round-off",
     "modified_theta": "static state to round-off",
     "newmark": "undamped vibration about the static state; no growth without friction"},
    tests=ALL, figure=("top sinking, error vs ρgH²/2E",
                       lambda s: fmt(s["stability"]["compression_error"]))))

# --- A very stiff block hitting at high speed: steel, 50 m/s; contact
# 2H/c = 2e-5 s = 2 steps.
CASES.append(Case(
    "stiff_fast", "Stiff (steel) at 50 m/s",
    {"Material": {"Young's modulus": "2e11", "Density": "7800"},
     "Initial conditions": {"Vertical velocity": "-50"}},
    time("1e-5", "2e-3"), time("1e-5", "2e-2"),
    {**{s: checks(penetration="1e-12", **NO_GROWTH)
        for s in ["theta_05", "theta_055", "theta_euler"]},
     "modified_theta": checks(penetration="2.3e-4", max_energy_ratio="1"),
     "newmark": checks(penetration="1e-12", min_energy_ratio="1.5")},
    {"theta_05": "energy conserved; leaves at 0.61 v0 plus vibration",
     "theta_055": "leaves at about half the speed",
     "theta_euler": "strongly damped impact (2 steps of contact)",
     "modified_theta": "penetrates up to h(1-θ)v0; energy rises in the step after the impact",
     "newmark": "fails by nature: leaves faster than it came, energy doubles"},
    tests=ALL, figure=RESTITUTION))

# --- A very soft block (E = 1e4 Pa, c = 3.7 m/s) dropped at 0.1 m/s.
CASES.append(Case(
    "soft", "Soft (E = 10⁴ Pa)",
    {"Material": {"Young's modulus": "1e4"},
     "Initial conditions": {"Vertical velocity": "-0.1"}},
    time("1e-3", "2", "1"), time("1e-3", "10", "8"),
    {**{s: checks(penetration="1e-12", **NO_GROWTH,
                  **dict(AT_REST, reaction="1e-3")) for s in ["theta_055", "theta_euler"]},
     "modified_theta": checks(penetration="2.5e-5", max_energy_ratio="1",
                              **dict(AT_REST, reaction="1e-3")),
     "theta_05": checks(penetration="1e-12", **NO_GROWTH),
     "newmark": checks(min_energy_ratio="100")},
    {"theta_05": "energy conserved, keeps chattering on the plane",
     "theta_055": "settles",
     "theta_euler": "settles, never leaves the plane",
     "modified_theta": "penetrates 2e-5 m; settles",
     "newmark": "fails by nature: unbounded energy growth (10⁶ × in 10 s)"},
    tests=ALL, bounds_only=["theta_05", "newmark"], figure=RESTITUTION))

# --- Mass ratio 1000: a second block of the same size falls 1 cm onto the
# first, with 1000 times its density, and one 1000 times lighter.
for name, title, rho2 in [("heavy_on_light", "Mass ratio 1000 (heavy on light)", "1e6"),
                          ("light_on_heavy", "Mass ratio 1/1000 (light on heavy)", "1")]:
    growth = NO_GROWTH
    b = {s: checks(penetration="1e-12", impulse_balance="1e-6", **growth)
         for s in THETA}
    if name == "light_on_heavy":
        for s in DAMPED:
            b[s] = checks(penetration="1e-12", impulse_balance="1e-6",
                          **growth, **dict(AT_REST, reaction="1e-6"))
    # Started at rest, the energy is measured against the largest kinetic +
    # elastic energy: a ratio above 1.2 means it ended far above anything
    # the fall could give.
    b["newmark"] = checks(min_energy_ratio="1.2")
    CASES.append(Case(
        name, title,
        {"Body 2": {"Enabled": "true", "Gap above body 1": "0.01"},
         "Material of body 2": {"Young's modulus": "1e7", "Density": rho2,
                                "Poisson's ratio": "0.3"}},
        time("1e-4", "0.5"), time("1e-4", "1"),
        b,
        {"theta_05": "energy conserved" +
                     ("; the light block chatters" if name == "light_on_heavy" else ""),
         "theta_055": "the heavy block keeps bouncing on the light one" if name == "heavy_on_light" else "settles",
         "theta_euler": "the heavy block keeps bouncing on the light one" if name == "heavy_on_light" else "settles",
         "modified_theta": "the heavy block keeps bouncing on the light one" if name == "heavy_on_light" else "settles",
         "newmark": ("fails by nature: exponential energy growth, the state "
                     "overflows (NaN) at t = 0.74 s" if name == "heavy_on_light"
                     else "fails by nature: energy grows, the light block jumps")},
        tests=["theta_euler", "modified_theta", "newmark"] if name == "heavy_on_light"
        else ["theta_euler", "modified_theta"],
        bounds_only=["modified_theta", "newmark"],
        short_for={"newmark": time("1e-4", "0.15")},
        figure=("impulse balance error",
                lambda s: fmt(s["checks"]["impulse_balance_error"]))))

# --- Stick-slip: a flat stiff block (0.1 m x 0.01 m, E = 1e9 Pa: no
# rocking even at mu = 2) slides at v0 = 1 m/s, pushed forwards by f with
# f/m = 0.5 m/s^2: it sticks at t* = v0 / (mu g - f/m) (rigid block), or
# never for mu = 0 (then v(T) = v0 + (f/m) T exactly).
for mu in ["0", "0.1", "0.5", "1", "2"]:
    d = float(mu) * 9.81 - 0.5
    t_star = 1. / d if d > 0 else None
    T = f"{1.5 * t_star:.3g}" if t_star else "0.5"
    final = f"{1.2 * t_star:.3g}" if t_star else "0.25"
    h = "2e-4" if mu == "0.1" else "1e-4"
    if t_star:
        sliding = dict(stick_time="0.002", distance="0.005")
    else:
        # frictionless: the mean velocity follows v0 + (f/m) t up to the
        # round-off of K u with the rigid translation in u (eps ||K|| |u| h
        # per step)
        sliding = dict(final_velocity="1e-6", distance="1e-3")
    b = {s: checks(penetration="1e-12", coulomb="1e-9", increase_roundoff="100",
                   max_energy_ratio="1", **sliding,
                   **dict(AT_REST, reaction="1e-3", final_phase=final))
         for s in DAMPED}
    # theta = 0.5 fails this by nature: it chatters while the block slows
    # down and once it has stopped, so the stick time and the distance
    # depend on the chatter (17 % and 0.6 % off at mu = 2; at mu = 0.1 the
    # mean velocity need not reach 0). Without friction it is exact.
    b["theta_05"] = checks(penetration="1e-12", coulomb="1e-9",
                           **({} if t_star else sliding))
    b["newmark"] = checks(penetration="1e-12", coulomb="1e-9",
                          **({} if t_star else dict(final_velocity="1e-6")))
    CASES.append(Case(
        f"stick_slip_mu_{mu.replace('.', '')}", f"Stick-slip μ = {mu}",
        {"Geometry": {"Height": "0.01", "Number of cells up": "2"},
         # E = 1e9 Pa keeps the block from rocking at mu = 1 and 2; at
         # mu = 0.1 it slides 1 m, and 1e7 Pa keeps the round-off of its
         # energy (eps |K||u|^2) at 1e-8 instead of 1e-6.
         "Material": {"Young's modulus": "1e7" if mu == "0.1" else "1e9"},
         "Initial conditions": {"Horizontal velocity": "1"},
         "Loads": {"Push force": "0.005, 0"},
         "Obstacle": {"Friction coefficient": mu}},
        time(h, T), time(h, T),
        b,
        {"theta_05": "v(T) = v0 + (f/m) T exactly" if mu == "0" else
                     "fails by nature: chatters while slowing down and once "
                     "stopped; stick time and distance depend on the chatter",
         **{s: ("v(T) = v0 + (f/m) T exactly" if mu == "0" else
                "rigid-block stick time and distance") for s in DAMPED},
         "newmark": "fails by nature: the block starts to jump (energy gained "
                    "at contact releases); v_x still exact" if mu == "0" else
                    "fails by nature: the friction power is not sign-definite "
                    "(energy rises in steps), never sticks"},
        tests=(["theta_euler"] + (ALL if mu == "0.5" else [])) if t_star
        else ["theta_euler", "newmark"],
        bounds_only=["theta_05", "newmark"],
        figure=("stick time error" if t_star else "error of v(T)",
                (lambda s: fmt(s["stability"]["stick_time_error"], 2)
                 if s["stability"]["measured_stick_time"] >= 0 else "never sticks")
                if t_star else lambda s: fmt(s["stability"]["final_velocity_error"]))))

# --- Grazing incidence: v = (10, -0.01) m/s, no gravity, 0.1 mm above the
# plane. Without friction v_x stays 10 m/s; with friction the nodes slide
# all the time, so the tangential impulse is exactly mu times the normal one.
for mu in ["0", "0.5"]:
    b = {s: checks(penetration="1e-12", coulomb="1e-9", **NO_GROWTH) for s in THETA}
    b["newmark"] = checks(penetration="1e-12")
    CASES.append(Case(
        f"grazing_mu_{mu.replace('.', '')}", f"Grazing v = (10, −0.01), μ = {mu}",
        {"Geometry": {"Initial gap": "1e-4"},
         "Initial conditions": {"Horizontal velocity": "10", "Vertical velocity": "-0.01"},
         "Loads": {"Gravity": "0, 0"},
         "Obstacle": {"Friction coefficient": mu}},
        time("1e-4", "0.05"), time("1e-4", "0.2"),
        b,
        {s: "bounces off; " + ("v_x unchanged" if mu == "0" else "P_T = μ P_N")
         for s in ALL},
        tests=["theta_euler", "modified_theta"],
        figure=("P_T / P_N", lambda s: fmt(s["tangential_impulse"] / s["normal_impulse"], 3))))

# --- Many simultaneous contacts: a flat punch, 128 cells across (129
# contact nodes, Klarbring LCP of 387 rows), pressed by 100 N with mu = 0.5.
CASES.append(Case(
    "flat_punch", "Flat punch, 129 contact nodes",
    {"Geometry": {"Number of cells across": "128"},
     "Loads": {"Push force": "0, -100"},
     "Obstacle": {"Friction coefficient": "0.5"}},
    time("1e-4", "0.03", "0.02"), time("1e-4", "0.1", "0.05"),
    {**{s: checks(penetration="1e-12", coulomb="1e-9", **NO_GROWTH,
                  **dict(AT_REST, reaction="1e-2")) for s in DAMPED},
     "theta_05": checks(penetration="1e-12", coulomb="1e-9"),
     "newmark": checks(penetration="1e-12", coulomb="1e-9")},
    {"theta_05": "friction power not sign-definite: energy rises by 4e-5 in a step; chatters",
     "theta_055": "settles: stick in the middle, slip at the edges",
     "theta_euler": "settles: stick in the middle, slip at the edges",
     "modified_theta": "settles: stick in the middle, slip at the edges",
     "newmark": "fails by nature: chatters (13 active-set changes per step), energy grows"},
    tests=["theta_euler", "modified_theta"], bounds_only=["modified_theta"],
    figure=REACTION))

# --- A long run of repeated impacts: a coarse block (4 x 2 cells) dropped
# from 5 cm, bouncing under gravity, 10^4 steps (test) and 10^5 (long).
CASES.append(Case(
    "bounce", "Bouncing, 10⁵ steps",
    {"Geometry": {"Number of cells across": "4", "Number of cells up": "2",
                  "Initial gap": "0.05"}},
    time("1e-3", "10", "5"), time("1e-3", "100", "90"),
    {**{s: checks(penetration="1e-12", impulse_balance="1e-7", **NO_GROWTH, **AT_REST)
        for s in DAMPED},
     "theta_05": checks(penetration="1e-12", **NO_GROWTH),
     "newmark": checks(min_energy_ratio="1.2")},
    {"theta_05": "energy bounded; still bounces now and then at t = 90 to 100 s",
     "theta_055": "a few bounces, then rests; no drift",
     "theta_euler": "almost inelastic, rests; no drift",
     "modified_theta": "a few bounces, then rests; no drift",
     "newmark": "fails by nature: each impact adds energy, the block ends up tens of metres high"},
    tests=DAMPED + ["newmark"], bounds_only=["newmark"], figure=REACTION))


# --- The same far above the Courant limit in 1D: the two bars of the paper
# (section 6.1.1) with 10 and 100 times the cells at the paper's time step
# (c h / dx = 9 and 90). Exact: contact for 2L/c, energy passed on.
TWO_BARS = {
    "Geometry": {"Bar length": "0.254", "Initial gap": "0",
                 "Cross-section area": "6.4516e-4"},
    "Material": {"Young's modulus": "0.20684e12", "Density": "0.78957e4"},
    "Initial conditions": {"Impact velocity": "5.13588"},
    "Time stepping": {"Time step": "2.226e-6", "End time": "0.2e-3"},
}
TWO_BARS_CASES = []
for courant, cells in [(10, "200"), (100, "2000")]:
    b = {s: checks(err_f="0.05", max_energy_ratio="1") for s in DAMPED}
    # theta = 0.5 conserves the energy up to round-off
    b["theta_05"] = checks(err_f="0.05", max_energy_ratio="1.000000001")
    b["newmark"] = checks(min_energy_ratio="1.001")
    TWO_BARS_CASES.append(Case(
        f"two_bars_courant_{courant}", f"Two bars 1D, Courant number {courant}",
        merge(TWO_BARS, {"Geometry": {"Number of cells per bar": cells}}),
        {}, {}, b,
        {"theta_05": "energy conserved; contact velocity oscillates (err_v ~ 1)",
         "theta_055": "contact interval within a step, 6 % of the energy lost",
         "theta_euler": "contact interval within a step, 15 % of the energy lost",
         "modified_theta": "contact interval within a step, 6 % of the energy lost",
         "newmark": "fails by nature: gains energy, force oscillates (err_f ~ 0.5)"},
        tests=ALL, program="two_bars_1d"))


# ---------------------------------------------------------------------------
def test_name(case, scheme):
    return f"{case.name}_{scheme}"


def write_tests(top):
    written = []
    for case in CASES + TWO_BARS_CASES:
        folder = os.path.join(top, "tests", "stability")
        output = {"Output directory": "results", "VTU output": "false",
                  "Plot": "false", "Print performance data": "false"}
        if case.program != "block_on_plane":
            folder = os.path.join(folder, case.program)
        os.makedirs(folder, exist_ok=True)
        for scheme in case.tests:
            if case.program == "block_on_plane":
                output["Print figures of merit"] = ("false" if scheme in case.bounds_only
                                                    else "true")
            sections = merge(case.sections(scheme, "short"), {"Output": output})
            comment = (f"{case.title}, {SCHEMES[scheme][0]}: "
                       f"{case.behaviour[scheme]}.\n"
                       "Written by benchmarks/stability/run_stability.py "
                       "--write-tests; doc/stability.md explains the case and "
                       "its bounds.")
            path = os.path.join(folder, test_name(case, scheme) + ".prm")
            with open(path, "w") as f:
                f.write(prm_text(sections, comment, case.program))
            written.append(path)
    return written


def run_case(build, case, scheme, length, out_dir):
    """Run one case; returns (summary or None, exit code)."""
    executable = os.path.join(build, "bin", case.program)
    if not os.path.exists(executable):
        sys.exit(f"{executable} not found: build first (see README.md)")
    os.makedirs(out_dir, exist_ok=True)
    sections = merge(case.sections(scheme, length), {"Output": {
        "Output directory": out_dir, "VTU output": "false", "Plot": "false"}})
    prm = os.path.join(out_dir, "run.prm")
    with open(prm, "w") as f:
        f.write(prm_text(sections, "", case.program))
    result = subprocess.run([executable, prm], stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True)
    summary_file = os.path.join(out_dir, "summary.json")
    summary = None
    if os.path.exists(summary_file):
        with open(summary_file) as f:
            summary = json.load(f)
    message = ""
    if result.returncode != 0:
        lines = [l.strip() for l in result.stdout.splitlines() if l.strip()]
        after = [l for l in lines if not l.startswith("-") and
                 not l.startswith("Exception") and not l.startswith("Aborting")]
        message = after[-1] if after else "exit code %d" % result.returncode
    return summary, result.returncode, message


def row(case, scheme, summary, code, message):
    label = SCHEMES[scheme][0]
    if summary is None:
        return (f"| {label} | — | — | — | — | — | — | **no result**: {message} | "
                f"{case.behaviour[scheme]} |")
    st = summary["stability"]
    verdict = "pass" if code == 0 else ("**fails**: " + message if "Verification" not in message
                                        else "checks fail")
    return ("| " + " | ".join([
        label,
        fmt(st["max_penetration"]),
        fmt(st["energy_change"]),
        fmt(st["max_energy_increase"]),
        fmt(st["active_set_changes_per_step"]),
        fmt(st["final_active_set_changes_per_step"]),
        case.figure[1](summary),
        verdict,
        case.behaviour[scheme]]) + " |")


def row_1d(case, scheme, summary, code, message):
    label = SCHEMES[scheme][0]
    if summary is None:
        return f"| {label} | — | — | — | **no result**: {message} | {case.behaviour[scheme]} |"
    verdict = "pass" if code == 0 else "checks fail"
    return ("| " + " | ".join([label, fmt(summary["err_v"], 3), fmt(summary["err_f"], 3),
                                fmt(summary["energy_ratio"], 6), verdict,
                                case.behaviour[scheme]]) + " |")


HEADER_1D = ("| scheme | err_v | err_f | energy ratio | checks | behaviour |\n"
             "|---|---|---|---|---|---|")

def header(case):
    return ("| scheme | max penetration [m] | energy change | largest rise in a step "
            "| active-set changes / step | same, final phase | " + case.figure[0] +
            " | checks | behaviour |\n|---|---|---|---|---|---|---|---|---|")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default="build")
    parser.add_argument("--out", default="doc")
    parser.add_argument("--cases", default="")
    parser.add_argument("--schemes", default="")
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--write-tests", action="store_true")
    args = parser.parse_args()
    top = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
    if args.write_tests:
        for path in write_tests(top):
            print(os.path.relpath(path, top))
        return
    cases = [c for c in CASES + TWO_BARS_CASES
             if not args.cases or c.name in args.cases.split(",")]
    schemes = [s for s in ALL if not args.schemes or s in args.schemes.split(",")]
    length = "short" if args.quick else "long"
    tables = []
    records = []
    with tempfile.TemporaryDirectory() as tmp:
        for case in cases:
            one_d = case.program != "block_on_plane"
            lines = [f"### {case.title} (`{case.name}`)", "", HEADER_1D if one_d else header(case)]
            for scheme in schemes:
                out = os.path.join(tmp, case.name, scheme)
                summary, code, message = run_case(args.build, case, scheme, length, out)
                records.append({"case": case.name, "scheme": scheme, "exit_code": code,
                                "message": message,
                                "has_summary": summary is not None})
                lines.append((row_1d if one_d else row)(case, scheme, summary, code, message))
                print(lines[-1], flush=True)
            tables.append("\n".join(lines))
    write_summary(records, length)
    if args.quick or args.cases or args.schemes:
        return
    write_page(os.path.join(args.out, "stability.md"), tables)


def write_summary(records, length):
    """results/stability/summary.json (each run's exit code and message) and
    the RESULT line. A non-zero exit is what a hard case may give (a check
    that fails, a message): it is counted, not hidden."""
    os.makedirs("results/stability", exist_ok=True)
    with open("results/stability/summary.json", "w") as f:
        json.dump({"program": "run_stability", "length": length, "runs": records}, f,
                  indent=1)
    print("summary: results/stability/summary.json")
    nonzero = [r for r in records if r["exit_code"] != 0]
    print(f"RESULT program=run_stability length={length} "
          f"cases={len({r['case'] for r in records})} runs={len(records)} "
          f"nonzero_exits={len(nonzero)} "
          f"no_summary={sum(not r['has_summary'] for r in records)}")


def write_page(path, tables):
    with open(os.path.join(os.path.dirname(__file__), "stability_intro.md")) as f:
        intro = f.read()
    with open(path, "w") as f:
        f.write(intro.replace("@MACHINE@", runs.machine_and_commit()))
        f.write("\n## Results (long versions)\n\n")
        f.write("\n\n".join(tables) + "\n")
    print(f"wrote {path}")


if __name__ == "__main__":
    main()

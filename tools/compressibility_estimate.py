#!/usr/bin/env python3
"""The weak-compressibility error of the species for a case's kinetics (docs/compressibility.md).

A weakly compressible flow drives the channel with a pressure drop; its density falls from inlet
to outlet by the fraction g = 2 nu u_max L / (R^2 c0^2). Along a streamline at the section-mean
speed U = 2/3 u_max the fluid then speeds up as u(s) = U (1 + g s / L) (mass flux conserved) and
the species obeys eq. (12) of the paper with its dilatation term:

    dC/ds = -R(C) / u(s) - C u'(s) / u(s).

This integrates that streamline twice, with and without the density drop, and prints the
relative change of C at the stations: the part of a WCSPH run's error that the flow model makes,
independent of resolution. For first-order kinetics it is the closed form of
docs/compressibility.md; for near-zero-order kinetics (Michaelis-Menten with C >> km) the
shorter time to react no longer offsets the dilution, and the error is larger.

Usage: tools/compressibility_estimate.py CASE.toml [--set key=value ...]
       tools/compressibility_estimate.py --self-test
"""
import argparse
import math
import sys
import tomllib

STATIONS = (25.0, 50.0, 100.0)
# The engine's defaults for the keys a case file may leave out (include/adrsph/case.hpp).
DEFAULTS = {
    "geometry.length": 100.0,
    "geometry.half_width": 5.0,
    "fluid.nu": 15.0,
    "fluid.u_bulk": 100.0,
    "fluid.c0_factor": 10.0,
    "species.c_in": 2.0,
    "species.k": 1.462,
}


class EstimateError(Exception):
    """A case this estimate cannot model: the message names the key."""


def flatten(table, prefix=""):
    out = {}
    for key, value in table.items():
        if isinstance(value, dict):
            out.update(flatten(value, prefix + key + "."))
        else:
            out[prefix + key] = value
    return out


def rate_law(keys, reactions):
    """R(C) of the case: species.k (first order) plus every [[reaction]] table. species.k
    defaults to 0 when the case has tables (cases/README.md)."""
    k1 = float(keys.get("species.k", 0.0 if reactions else DEFAULTS["species.k"]))
    laws = []
    for i, r in enumerate(reactions):
        if r.get("zones"):
            raise EstimateError(f"reaction[{i}]: zones are not modelled by this estimate "
                             "(it follows one streamline at the section-mean speed)")
        law, k = r.get("law", "first_order"), float(r.get("k", 0.0))  # cases/README.md
        if law == "first_order":
            laws.append(lambda c, k=k: k * c)
        elif law == "nth_order":
            n = float(r.get("order", 1.0))
            laws.append(lambda c, k=k, n=n: k * max(c, 0.0) ** n)
        elif law == "michaelis_menten":
            km = float(r.get("km", 0.0))
            laws.append(lambda c, k=k, km=km: k * max(c, 0.0) / max(km + max(c, 0.0), 1e-300))
        else:
            raise EstimateError(f"reaction[{i}].law: unknown law {law!r}")
    return lambda c: k1 * c + sum(f(c) for f in laws)


def density_drop(nu, u_max, length, half_width, c0):
    """g = 2 nu u_max L / (R^2 c0^2): the fraction by which the density of the WCSPH flow falls
    from inlet to outlet (docs/compressibility.md)."""
    return 2.0 * nu * u_max * length / (half_width ** 2 * c0 ** 2)


def first_order_closed_form(g, k, x, length, u_mean):
    """dC / C at x for first-order kinetics to first order in g (docs/compressibility.md): the
    dilution -g x / L, offset by the shorter time to react, (k x / u) g x / (2 L)."""
    return -g * x / length + (k * x / u_mean) * g * x / (2.0 * length)


def streamline(rate, c_in, u_mean, g, length, stations, steps=20000):
    """C at the stations along the streamline (classical Runge-Kutta in s)."""
    def rhs(s, c):
        u = u_mean * (1.0 + g * s / length)
        return -rate(c) / u - c * (u_mean * g / length) / u

    out, c, s = {}, c_in, 0.0
    targets = sorted(stations)
    for x_end in targets:
        n = max(1, int(round(steps * (x_end - s) / length)))
        ds = (x_end - s) / n
        for _ in range(n):
            k1 = rhs(s, c)
            k2 = rhs(s + ds / 2, c + ds / 2 * k1)
            k3 = rhs(s + ds / 2, c + ds / 2 * k2)
            k4 = rhs(s + ds, c + ds * k3)
            c += ds / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
            s += ds
        out[x_end] = c
    return out


def estimate(keys, reactions):
    """{x: relative change of C at x}, {x: incompressible C at x}."""
    merged = {**DEFAULTS, **keys}

    def number(key):
        try:
            return float(merged[key])
        except (TypeError, ValueError):
            raise EstimateError(f"key '{key}': expected a number, got {merged[key]!r}") from None

    u_max = 2.0 * number("fluid.u_bulk")
    c0 = number("fluid.c0_factor") * u_max
    length, half = number("geometry.length"), number("geometry.half_width")
    g = density_drop(number("fluid.nu"), u_max, length, half, c0)
    # fluid.driving = "body_force" carries the pressure drop by a body force: no density drop.
    if merged.get("fluid.driving", "pressure") == "body_force":
        g = 0.0
    rate = rate_law(keys, reactions)
    xs = [x for x in STATIONS if x <= length]
    u_mean = 2.0 * u_max / 3.0
    c_in = number("species.c_in")
    comp = streamline(rate, c_in, u_mean, g, length, xs)
    inc = streamline(rate, c_in, u_mean, 0.0, length, xs)
    return {x: comp[x] / inc[x] - 1.0 for x in xs}, inc, g


def parse_value(text):
    try:
        return tomllib.loads("v = " + text)["v"]
    except tomllib.TOMLDecodeError:
        return text


def self_test():
    failures = 0

    def check(what, ok):
        nonlocal failures
        print(("ok   " if ok else "FAIL ") + what)
        failures += 0 if ok else 1

    # First order: the closed form of docs/compressibility.md, -g x/L + (k x/u) g x/(2L),
    # to the order it keeps (g^2 and (k x/u)^2 g terms are below 1e-4 here).
    keys = {"species.k": 1.462}
    rel, _, g = estimate(keys, [])
    check(f"g = 0.006 for the reactor (got {g:.6f})", abs(g - 0.006) < 1e-12)
    for x, v in rel.items():
        closed = first_order_closed_form(g, 1.462, x, 100.0, 400.0 / 3.0)
        check(f"first order at x = {x:g}: {100 * v:+.4f}% against the closed form "
              f"{100 * closed:+.4f}%", abs(v - closed) < 1e-4)
    # No reaction: pure dilution, C u = const along the streamline, so C / C_inc = 1 / (1 + g x/L).
    rel, _, g = estimate({"species.k": 0.0}, [])
    for x, v in rel.items():
        exact = 1.0 / (1.0 + g * x / 100.0) - 1.0
        check(f"no reaction at x = {x:g}: {v:.3e} against {exact:.3e}", abs(v - exact) < 1e-9)
    # A first-order [[reaction]] table is the same as species.k.
    a, _, _ = estimate({"species.k": 1.462}, [])
    b, _, _ = estimate({}, [{"law": "first_order", "k": 1.462}])
    check("a first-order table equals species.k", all(abs(a[x] - b[x]) < 1e-12 for x in a))
    # Zero order (Michaelis-Menten, km -> 0): dilution is not offset by the reaction, so the
    # change is larger in magnitude than first order's at the outlet.
    z, inc, _ = estimate({}, [{"law": "michaelis_menten", "k": 1.0, "km": 1e-9}])
    check(f"zero order outlet {100 * z[100.0]:+.3f}% below first order's {100 * a[100.0]:+.3f}%",
          z[100.0] < a[100.0])
    # Zero order, closed form: d(C u)/ds = -k, so C(s) = (C_in U - k s) / u(s).
    g = 0.006
    for x in (25.0, 50.0, 100.0):
        u = 400.0 / 3.0
        c = (2.0 * u - 1.0 * x) / (u * (1.0 + g * x / 100.0))
        check(f"zero order at x = {x:g}: {inc[x] * (1 + z[x]):.8f} against {c:.8f}",
              abs(inc[x] * (1 + z[x]) - c) < 1e-7)
    rel, _, g = estimate({"species.k": 1.462, "fluid.driving": "body_force"}, [])
    check(f"no density drop with fluid.driving = body_force (g = {g:g})",
          g == 0.0 and all(v == 0.0 for v in rel.values()))
    print("self-test: " + ("passed" if failures == 0 else f"{failures} failed"))
    return 1 if failures else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("case", nargs="?", help="case file (TOML)")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="override a case key, as adrsph run --set (dotted key)")
    ap.add_argument("--self-test", action="store_true", help="check against closed forms")
    args = ap.parse_args()
    if args.self_test:
        return self_test()
    if not args.case:
        ap.error("a case file is needed (or --self-test)")
    try:
        with open(args.case, "rb") as f:
            doc = tomllib.load(f)
    except (OSError, tomllib.TOMLDecodeError) as e:
        print(f"{args.case}: {e}", file=sys.stderr)
        return 2
    reactions = doc.pop("reaction", [])
    keys = flatten(doc)
    for item in args.set:
        if "=" not in item:
            print(f"--set {item}: expected KEY=VALUE", file=sys.stderr)
            return 2
        key, value = item.split("=", 1)
        keys[key.strip()] = parse_value(value.strip())
    if keys.get("flow") == "prescribed":
        print("flow = \"prescribed\": an incompressible flow, no weak-compressibility error")
        return 0
    try:
        rel, inc, g = estimate(keys, reactions)
    except EstimateError as e:
        print(f"{args.case}: {e}", file=sys.stderr)
        return 2
    print(f"{args.case}: density drop along the channel g = {g:.5f}")
    print("x [mm]   C incompressible   change from weak compressibility")
    for x in rel:
        print(f"{x:6g}   {inc[x]:16.6f}   {100 * rel[x]:+.3f}%")
    return 0


if __name__ == "__main__":
    sys.exit(main())

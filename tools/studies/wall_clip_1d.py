#!/usr/bin/env python3
"""The plate's rebound (tools/studies/impact_rebound.py) in one dimension, outside the engine.

A short MLS-MPM of an elastic bar (h = 0.12 m, E = 1 MPa, 1620 kg/m3, two particles per cell,
quadratic B-splines, APIC's affine velocity, the stress fused into P2G as the engine does)
striking a wall at 1.82 m/s: the wall node's normal velocity is set to zero where it points into
the wall, as engine/contact_laws.h's slip law does. Printed per h/dx, at the CFL step (0.4) and at
held steps of 1e-4 and 3e-5 s:
  wall   the rebound speed over the impact speed (an elastic bar on a rigid wall keeps it all)
  flip   the same with FLIP 0.99 (the particles keep their velocity between steps)
  reach  the wall node acts only once a particle is within half a cell of the wall (the node
         beyond it has mass), not from the 1.5 cells the stencil reaches: a candidate mend
  penalty no node rule: a spring force E/dx per unit overlap pushes each particle within half a
         cell of the wall (the contact at the particles; its stiffness is the cell's own, so it
         keeps within the CFL step)
  mirror two such bars meeting head on, no wall (the midplane is the wall's mirror image): the
         kinetic energy regained after the first compression over the impact's (the grid joins
         the bars, so not a rebound; compare the wall's rebound squared)
The one-dimensional code loses the rebound with the step as the engine's plate does, so the cause
is the scheme's, not the engine's: see docs/impulse_waves.md, "The landing: a wall takes more the
more steps it acts". Runs in a few seconds:  python3 tools/studies/wall_clip_1d.py
"""
import numpy as np

H, E, RHO, SPEED, PPC = 0.12, 1e6, 1620.0, 1.82, 2


def weights(xp, dx):
    base = np.floor(xp / dx - 0.5).astype(int)
    fx = xp / dx - base
    return base, fx, (0.5 * (1.5 - fx) ** 2, 0.75 - (fx - 1) ** 2, 0.5 * (fx - 0.5) ** 2)


def step(xp, vp, Cp, Fp, mp, vol, dx, dt, wall, flip, reach=False, penalty=False):
    """One MLS-MPM step; the wall (x <= 0) takes the normal velocity into it (with `reach`, only
    once a particle is within half a cell of it; with `penalty`, it pushes the particles instead)."""
    base, fx, w = weights(xp, dx)
    lo = base.min()
    nn = base.max() + 3 - lo
    m, mom, free = np.zeros(nn), np.zeros(nn), np.zeros(nn)
    affine = mp * Cp - dt * vol * E * (Fp - 1) * 4 / dx ** 2  # APIC's C and the fused stress
    push = dt * E / dx * np.maximum(0.0, 0.5 * dx - xp) if penalty else np.zeros_like(xp)
    for i in range(3):
        idx, d = base + i - lo, (i - fx) * dx
        np.add.at(m, idx, w[i] * mp)
        np.add.at(mom, idx, w[i] * (mp * vp + affine * d + push))
        np.add.at(free, idx, w[i] * (mp * vp + mp * Cp * d))
    has = m > 0
    vg = np.where(has, mom / np.where(has, m, 1), 0)
    v_old = np.where(has, free / np.where(has, m, 1), 0)
    if wall and not penalty and (not reach or xp.min() <= 0.5 * dx):
        on_wall = (np.arange(nn) + lo) * dx <= 1e-12
        vg = np.where(on_wall & (vg < 0), 0, vg)
    pic, dv, C = np.zeros_like(vp), np.zeros_like(vp), np.zeros_like(vp)
    for i in range(3):
        idx, d = base + i - lo, (i - fx) * dx
        pic += w[i] * vg[idx]
        dv += w[i] * (vg[idx] - v_old[idx])
        C += w[i] * vg[idx] * d * 4 / dx ** 2
    vp = flip * (vp + dv) + (1 - flip) * pic
    return xp + dt * vp, vp, C, Fp * (1 + dt * C)


def bar(cells, gap):
    dx = H / cells
    n = int(round(cells * PPC))
    return dx, gap + (np.arange(n) + 0.5) * H / n, H / n


def wall_rebound(cells, dt, flip=0.0, t_end=0.06, reach=False, penalty=False):
    dx, xp, vol = bar(cells, 0.04)
    vp, Cp, Fp = np.full(len(xp), -SPEED), np.zeros(len(xp)), np.ones(len(xp))
    for _ in range(int(t_end / dt)):
        xp, vp, Cp, Fp = step(xp, vp, Cp, Fp, RHO * vol, vol, dx, dt, True, flip, reach, penalty)
    return vp.mean() / SPEED


def mirror_energy(cells, dt, t_end=0.012):
    dx, x, vol = bar(cells, 1e-9)
    xp = np.concatenate([-x[::-1], x]) + 0.3  # the midplane on a node row, as the wall is
    vp = np.concatenate([np.full(len(x), SPEED), np.full(len(x), -SPEED)])
    Cp, Fp, ke = np.zeros(len(xp)), np.ones(len(xp)), []
    for _ in range(int(t_end / dt)):
        xp, vp, Cp, Fp = step(xp, vp, Cp, Fp, RHO * vol, vol, dx, dt, False, 0.0)
        ke.append((vp ** 2).mean() / SPEED ** 2)
    return max(ke[len(ke) // 3:])  # after the first compression (about 2 h / c = 8 ms)


def main():
    c = np.sqrt(E / RHO)
    print("h/dx  case    CFL 0.4  1e-4 s  3e-5 s")
    for cells in (3.2, 6.4, 12.8):
        steps = (0.4 * H / cells / c, 1e-4, 3e-5)
        for name, f in (("wall", wall_rebound), ("flip", lambda n, d: wall_rebound(n, d, 0.99)),
                        ("reach", lambda n, d: wall_rebound(n, d, reach=True)),
                        ("penalty", lambda n, d: wall_rebound(n, d, penalty=True)),
                        ("mirror", mirror_energy)):
            print(f"{cells:<5} {name:<7} " + "  ".join(f"{f(cells, dt):.3f} " for dt in steps), flush=True)


if __name__ == "__main__":
    main()

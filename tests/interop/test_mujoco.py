"""MuJoCo models of scenes, checked in MuJoCo itself: the loops closed by MuJoCo's own
equality constraints (Gauss-Newton on its residuals and Jacobians) put every point of the
four-bar, a slider-crank, Jansen's leg and the double butterfly where the scene's sweep
does, to 1e-6 of the scene's size, over the sweep's turn; the position servo driven with
mj_step follows within 1e-6 too, away from dead points."""

from __future__ import annotations

import xml.etree.ElementTree as ET

import numpy as np
import planarkin as pk
import pytest
from planarkin.face.cli import main
from planarkin.interop import mujoco as mjcf

SCENES = ["fourbar", "slider-crank", "jansen", "double-butterfly-1", "double-butterfly-2"]


def test_mjcf_structure_without_mujoco() -> None:
    """The tree and its closures, read with xml.etree (no MuJoCo needed)."""
    sc = pk.scenes.load("jansen")
    root = ET.fromstring(mjcf.build(sc).xml)
    joints = root.findall(".//body/joint")
    assert all(j.get("type") == "hinge" and j.get("axis") == "0 0 1" for j in joints)
    connects = root.findall("./equality/connect")
    # 8 links, 10 pin pairs (Z and M and C join three links each): 7 in the tree
    assert len(joints) == 7 and len(connects) == 3
    assert root.find("./actuator/position").get("joint") == "hinge:O:crank"
    sites = {s.get("name") for s in root.iter("site")}
    assert sites == {f"{ln}:{p}" for ln, v in sc.links.items() for p in v}


def test_slider_crank_closes_with_a_block() -> None:
    root = ET.fromstring(mjcf.build(pk.scenes.load("slider-crank")).xml)
    block = root.find(".//body[@name='block:piston']")
    assert block is not None and block.find("joint").get("type") == "slide"
    assert block.find("joint").get("axis") == "1.0 0.0 0"
    c = root.find("./equality/connect")
    assert (c.get("body1"), c.get("body2")) == ("block:piston", "rod")


def _replay(name: str):  # noqa: ANN202
    pytest.importorskip("mujoco", reason="the mujoco extra is not installed")
    from planarkin.interop.mujoco_replay import Replay

    sc = pk.scenes.load(name)
    return sc, sc.sweep(outputs=list(sc.points)), Replay(sc)


@pytest.mark.parametrize("name", SCENES)
def test_replay_in_mujoco_matches_the_sweep(name: str) -> None:
    sc, sw, rp = _replay(name)
    got = rp.replay(sw)
    solved = sw.success
    assert solved.sum() >= 80
    err = 0.0
    for site, path in got.items():
        point = site.split(":", 1)[1]
        assert not np.isnan(path[solved]).any(), site
        err = max(err, float(np.abs(path[solved] - sw.points[point][solved]).max()))
    assert err <= 1e-6 * rp.size, err / rp.size


@pytest.mark.parametrize("name", SCENES)
def test_servo_dynamics_follow_the_scene(name: str) -> None:
    """mj_step with the position actuator: each point where the scene puts it for the input
    the joint actually reached (MuJoCo's soft constraints and the servo's lag), away from
    the dead point that ends a double butterfly's run."""
    sc, sw, rp = _replay(name)
    run = int(np.argmin(sw.success)) if not sw.success.all() else len(sw.theta)
    offsets = sw.theta[:run] - rp.start
    reached, pos = rp.simulate(offsets, steps=200)
    ref = sc.sweep(reached + rp.start, outputs=list(sc.points))
    keep = slice(0, run if run == len(sw.theta) else run - 3)
    assert ref.success[keep].all()
    for i, site in enumerate(rp.sites):
        point = site.split(":", 1)[1]
        err = np.abs(pos[keep, i] - ref.points[point][keep]).max() / rp.size
        assert err <= 1e-4 if name.startswith("double") else err <= 1e-6, (site, err)


def test_export_cli_writes_a_model_mujoco_loads(tmp_path) -> None:  # noqa: ANN001
    path = tmp_path / "leg.xml"
    assert main(["export", "jansen", "--to", str(path)]) == 0
    mujoco = pytest.importorskip("mujoco", reason="the mujoco extra is not installed")
    m = mujoco.MjModel.from_xml_path(str(path))
    assert (m.nq, m.neq, m.nu) == (7, 3, 1)


@pytest.mark.parametrize("name", pk.scenes.names())
def test_every_built_in_scene_replays(name: str) -> None:
    """Slots and prismatic pairs too (blocks connect-ed and weld-ed, slides in the tree),
    linear inputs: within 1e-9 of the size but at a linear input's stroke ends, which are
    dead points (SINGULAR in the sweep)."""
    sc, sw, rp = _replay(name)
    got = rp.replay(sw)
    ok = sw.success.copy()
    if sw.input == "displacement":
        ok[[0, -1]] = False
    for site, path in got.items():
        point = site.split(":", 1)[1]
        err = np.abs(path[ok] - sw.points[point][ok]).max() / rp.size
        assert err <= 1e-9, (site, err)
    if sw.input == "displacement":
        # the stroke's ends are dead points (SINGULAR: no pose) or limits (solved)
        assert np.isin(sw.status[[0, -1]], [pk.Status.SINGULAR, pk.Status.CONVERGED]).all()


@pytest.mark.parametrize("name", ["fourbar-loaded", "jansen-loaded", "engine"])
def test_masses_and_gravity_come_from_the_scenes_loads(name: str, tmp_path) -> None:  # noqa: ANN001
    """MuJoCo reads each link's mass, its centre (world coordinates at the drawn pose) and
    its moment of inertia about it as the scene's loads give them, and the gravity."""
    mujoco = pytest.importorskip("mujoco", reason="the mujoco extra is not installed")
    sc = pk.scenes.load(name)
    loads = sc.loads
    m = mujoco.MjModel.from_xml_path(str(mjcf.write(sc, tmp_path / f"{name}.xml")))
    d = mujoco.MjData(m)
    mujoco.mj_kinematics(m, d)
    mujoco.mj_comPos(m, d)
    for link, spec in (loads.get("masses") or {}).items():
        body = m.body(link)
        assert body.mass[0] == pytest.approx(spec["mass"], rel=1e-12)
        c = spec["center"]
        centre = sc.points[c] if isinstance(c, str) else c
        np.testing.assert_allclose(d.xipos[body.id][:2], centre, rtol=0, atol=1e-9)
        assert body.inertia[2] == pytest.approx(spec["inertia"], rel=1e-9, abs=1e-15)
    g = loads.get("gravity") or [0.0, 0.0]
    np.testing.assert_allclose(m.opt.gravity, [g[0], g[1], 0.0], rtol=0, atol=0)

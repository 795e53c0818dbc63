"""`taebp snapshot` pictures carry the simulated time and a legend of the
vehicle colours below sumo-gui's view; --no-legend keeps sumo-gui's picture."""
import os

from PIL import Image

from conftest import PAPER, cli

LEGEND = {(0, 0, 255), (255, 0, 0), (255, 220, 0), (0, 200, 0), (255, 140, 0), (255, 0, 255)}


def near(pixel, rgb, tol=40):
    return all(abs(a - b) <= tol for a, b in zip(pixel, rgb))


def test_snapshot_has_a_legend_strip_with_every_colour_and_the_time(tmp_path):
    env_display = os.environ.pop("DISPLAY", None)  # headless: xvfb-run
    try:
        r = cli("snapshot", PAPER, "--policy", "ta_ebp", "--at", 20, "--out", tmp_path / "a.png")
        cli("snapshot", PAPER, "--policy", "ta_ebp", "--at", 20, "--out", tmp_path / "raw.png",
            "--no-legend")
    finally:
        if env_display is not None:
            os.environ["DISPLAY"] = env_display
    assert "snapshot of ta_ebp at t = 20 s" in r.stderr
    raw = Image.open(tmp_path / "raw.png").convert("RGB")
    pic = Image.open(tmp_path / "a.png").convert("RGB")
    w, h = raw.size
    # The view unchanged on top, a strip below it.
    assert pic.size[0] == w and pic.size[1] > h + 40
    assert list(pic.crop((0, 0, w, h)).getdata()) == list(raw.getdata())
    strip = pic.crop((0, h, w, pic.size[1]))
    colours = set(strip.getdata())
    assert LEGEND <= colours, LEGEND - colours  # one exact swatch per colour
    dark = sum(1 for p in strip.getdata() if sum(p) < 150)
    assert dark > 1000, "no text in the legend strip"
    # The scene shows the colours the legend explains: at t = 20 s av2 holds
    # after its nudge (yellow) and hv7 chose DC (green).
    scene = list(raw.getdata())
    assert any(near(p, (255, 220, 0)) for p in scene)
    assert any(near(p, (0, 200, 0)) for p in scene)
    # No temporary picture left next to the output.
    assert sorted(os.listdir(tmp_path)) == ["a.png", "raw.png"]

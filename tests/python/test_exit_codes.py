"""One list of exit codes and error kinds (base/exit_codes.h): every Python
exception carries the code `taebp` exits with for the same error, and the
README's table says the same."""
import os
import re

import pytest

import taebp
from conftest import ROOT, cli


def readme_codes():
    """code -> meaning from the manual's "Exit codes" table (docs/cli.md)."""
    with open(os.path.join(ROOT, "docs", "cli.md"), encoding="utf-8") as f:
        text = f.read()
    table = text[text.index("Exit codes, for every subcommand"):]
    table = table[:table.index("\n\n", table.index("| code |"))]
    rows = {}
    lines = [l for l in table.splitlines() if l.startswith("|")]
    for line in lines[2:]:  # after the header and its rule
        cells = [c.strip() for c in line.strip("|").split("|")]
        for code in cells[0].split(","):
            rows[int(code)] = cells[1]
    return rows


def test_every_exception_has_the_documented_code():
    expected = {taebp.ConfigError: 2, taebp.InvalidArgument: 2, taebp.OutputError: 2,
                taebp.SumoError: 3, taebp.StallError: 4, taebp.BusyError: 1,
                taebp.SweepError: 1, taebp.Interrupted: 130}
    documented = readme_codes()
    for exc, code in expected.items():
        assert exc.exit_code == code, exc.__name__
        assert code in documented, (exc.__name__, code)
    assert issubclass(taebp.Interrupted, KeyboardInterrupt)
    assert set(taebp.EXIT_CODES.values()) <= set(documented)


def test_the_cli_and_python_agree_on_a_config_error(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("scenario: {duration: -1}\n")
    r = cli("run", bad, "--out", tmp_path / "out", check=False)
    with pytest.raises(taebp.ConfigError) as e:
        taebp.run(str(bad))
    assert r.returncode == e.value.exit_code == 2
    assert re.search(r"scenario\.duration", str(e.value))
    assert "taebp: config error: " in r.stderr


def test_the_cli_and_python_agree_on_an_output_error(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    out = blocker / "below"
    cfg = os.path.join(ROOT, "configs", "paper.yaml")
    r = cli("run", cfg, "--set", "scenario.duration=1", "--out", out, check=False)
    with pytest.raises(taebp.OutputError) as e:
        taebp.run(cfg, ["scenario.duration=1"], out=str(out))
    assert r.returncode == e.value.exit_code == 2

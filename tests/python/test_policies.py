"""The policy table from Python: taebp.policy_table() is `taebp policies`, the
docstrings that list policies list the table's, every game policy predicts,
and tools/plot colours and labels every policy of the table."""
import re

import pytest

import taebp
from conftest import cli_json


def test_policies_is_the_cli_table():
    rows = taebp.policy_table()
    assert rows == cli_json("policies", "--print", "json")
    names = [r["name"] for r in rows]
    assert len(names) == len(set(names)) == 9
    assert [r["name"] for r in rows if not r["plays_game"]] == ["sumo_native"]
    assert [r["name"] for r in rows if r["by_default"]] == ["no_ebp", "no_trust", "ta_ebp"]
    native = rows[names.index("sumo_native")]
    assert "model" in native["ignores"]


def test_docstrings_list_the_tables_policies():
    rows = taebp.policy_table()
    games = [r["name"] for r in rows if r["plays_game"]]
    listed = re.search(r"``policy`` \(([^:]*):", taebp.predict.__doc__).group(1)
    assert re.sub(r"\s+", " ", listed).split(", ") == games
    assert ", ".join(r["name"] for r in rows) in taebp.policy_table.__doc__
    assert taebp.policies() == [r["name"] for r in rows]
    # theory()'s policies: the ones its docstring names, all in the table.
    named = re.search(r"policies\.<([^>]*)>", taebp.theory.__doc__).group(1)
    named = [n.strip() for n in re.sub(r"\s+", " ", named).split("|")]
    assert named == list(taebp.theory()["policies"])
    assert set(named) <= set(games)


@pytest.mark.parametrize("name", [r["name"] for r in taebp.policy_table() if r["plays_game"]])
def test_every_game_policy_predicts(name):
    p = taebp.predict(name, trust=0.6)
    assert 0.0 <= p["dc_rate"] <= 1.0


def test_predict_names_the_choices_for_a_policy_without_a_game():
    with pytest.raises(taebp.InvalidArgument, match="plays no game.*ta_ebp_learned"):
        taebp.predict("sumo_native")
    with pytest.raises(taebp.InvalidArgument, match="'bogus' is unknown"):
        taebp.predict("bogus")


def test_plot_colours_and_labels_every_policy():
    """The figures' colour and label of every policy are the policy table's
    (tables.json is the program's table, written by tools/refresh-docs); one
    colour each; a policy the table does not know keeps its name."""
    from taebp.plot import style
    rows = taebp.policy_table()
    assert [p["name"] for p in style.tables()["policies"]] == [r["name"] for r in rows]
    for r in rows:
        assert style.style(r["name"]) == (r["colour"], r["label"])
    assert len({r["colour"] for r in rows}) == len(rows)
    assert style.style("my_policy")[1] == "my_policy"

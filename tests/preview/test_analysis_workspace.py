"""Which scene a part belongs to (castor.analysis.workspace): the scene at the
top of the #include chains that reach it, among the workspace's *.cas files."""

from pathlib import Path

from castor.analysis.workspace import scenes_including


def test_the_scene_at_the_top_of_the_chain(tmp_path: Path):
    (tmp_path / "parts" / "deep").mkdir(parents=True)
    (tmp_path / "scene.cas").write_text('#include "parts/b.cas"\n> b;\n')
    (tmp_path / "parts" / "b.cas").write_text('  #  include "deep/c.cas"\nb = c;\n')
    (tmp_path / "parts" / "deep" / "c.cas").write_text("c = !cu(1, 0, 0);\n")
    (tmp_path / "alone.cas").write_text("> !cu(1, 0, 0);\n")
    (tmp_path / ".hidden").mkdir()
    (tmp_path / ".hidden" / "other.cas").write_text('#include "../parts/deep/c.cas"\n')
    scene = str((tmp_path / "scene.cas").resolve())
    assert scenes_including(str(tmp_path / "parts" / "deep" / "c.cas"), [str(tmp_path)]) == [scene]
    assert scenes_including(str(tmp_path / "parts" / "b.cas"), [str(tmp_path)]) == [scene]
    assert scenes_including(str(tmp_path / "scene.cas"), [str(tmp_path)]) == []
    assert scenes_including(str(tmp_path / "alone.cas"), [str(tmp_path)]) == []
    # a comment or a string that names the file is no #include
    (tmp_path / "mention.cas").write_text('// #include "alone.cas"\n> !cu(1, 0, 0);\n')
    assert scenes_including(str(tmp_path / "alone.cas"), [str(tmp_path)]) == []


def test_a_cycle_still_names_a_scene(tmp_path: Path):
    (tmp_path / "a.cas").write_text('#ifndef A\n#define A\n#include "b.cas"\n#endif\n')
    (tmp_path / "b.cas").write_text('#include "a.cas"\n')
    found = scenes_including(str(tmp_path / "b.cas"), [str(tmp_path)])
    assert found == [str((tmp_path / "a.cas").resolve())]

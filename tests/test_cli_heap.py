"""The command's garbage-collection policy (tribodyn.cli.heap)."""

import atexit
import gc

from tribodyn.cli import heap


def test_long_lived_heap_freezes_for_the_block_and_gives_the_heap_back():
    assert gc.get_freeze_count() == 0
    before = [object() for _ in range(3)]  # noqa: F841  (kept alive)
    with heap.long_lived_heap() as keep:
        frozen = gc.get_freeze_count()
        assert frozen > 0
        later = [[] for _ in range(1000)]  # tracked containers made in the block
        keep()
        assert gc.get_freeze_count() >= frozen + len(later)
    assert gc.get_freeze_count() == 0


def test_the_heap_is_given_back_when_the_block_fails():
    try:
        with heap.long_lived_heap():
            raise RuntimeError("a failed study")
    except RuntimeError:
        pass
    assert gc.get_freeze_count() == 0


def test_a_run_in_this_process_leaves_nothing_frozen(plain_run):
    # the fixture ran `tribodyn run` through the application in this process
    assert (plain_run / "summary.json").is_file()
    assert gc.get_freeze_count() == 0


def test_the_command_freezes_at_exit_only(monkeypatch):
    registered = []
    monkeypatch.setattr(atexit, "register", registered.append)
    heap.skip_collections_at_exit()
    assert registered == [gc.freeze]
    assert gc.get_freeze_count() == 0  # nothing frozen before the exit

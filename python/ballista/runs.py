"""ballista.run: a deck run in this process by the same run loop as `ballista run`."""
import os

from . import _ballista
from ._decks import deck_source, override_strings
from .results import Results


def run(deck=None, out_dir=None, *, overrides=None, threads=0, overwrite=False, plots=False, quiet=False,
        progress=None, progress_interval=0.5, base_dir=None, restart=None):
    """Runs `deck` (a YAML file's path, or a dict with the deck's sections) and returns its
    Results, whatever its status ("completed", "failed", "interrupted": check `.status`).

    out_dir      results folder; default out/<deck file's name> as on the command line (required
                 for a dict). A folder holding another run's files is replaced; one holding other
                 files is refused unless overwrite=True (docs/output.md, the results folder).
    overrides    {"key.path": value, "list.path+": item} or ["key.path=value", ...]: `--set`.
    threads      OpenMP threads (0: the deck's, else all cores).
    plots        draw the figures `ballista run` draws (penetration, fragments).
    quiet        nothing on the console but errors (warnings still go to summary.json).
    progress     callable(report) with report a dict: phase ("main" or "stage '<name>'"), time,
                 start, end (s), fraction, step, dt (s), eta_seconds (wall), eta_is_bound. Called at
                 a phase's first step and then at most every `progress_interval` wall seconds.
                 Returning False stops the run with a checkpoint (status "interrupted", continue
                 with run(restart=out_dir)); an exception it raises stops the run the same way and
                 is raised again here.
    base_dir     folder of a dict deck's relative paths (default: the working directory).
    restart      a results folder: continue its run from its newest checkpoint (no deck then;
                 overrides may change only the end time, outputs, checkpoints and limits).

    Ctrl-C (SIGINT) or SIGTERM during the steps checkpoints and stops the run, then raises
    KeyboardInterrupt. A bad deck raises DeckError (file, line, column, key_path); a run that
    cannot even start (memory, overlapping bodies) raises Error.
    """
    sets = override_strings(overrides)
    if restart is not None:
        if deck is not None or out_dir is not None:
            raise ValueError("restart continues the run in its own folder: give no deck and no out_dir")
        result = _ballista.restart_run(os.fspath(restart), sets, int(threads), bool(plots), bool(quiet), progress,
                                       float(progress_interval))
    else:
        if deck is None:
            raise ValueError("run: give a deck (a file or a dict), or restart=DIR")
        text, file_name = deck_source(deck, base_dir)
        if out_dir is None:
            if isinstance(deck, dict):
                raise ValueError("run: a deck given as a dict needs out_dir")
            out_dir = os.path.join("out", os.path.splitext(os.path.basename(file_name))[0])
        result = _ballista.run_deck(text, file_name, sets, os.fspath(out_dir), int(threads), bool(overwrite),
                                    bool(plots), bool(quiet), progress, float(progress_interval))
    if result["status"] == "interrupted" and result["interrupted_by"] == "signal":
        raise KeyboardInterrupt(result["error"])
    return Results(result["out_dir"], result)

"""Records of key numbers: what a notebook writes, for the build to compare and publish.

A notebook creates one :class:`Recorder`, records each key number together with the tolerance
that the numerics can guarantee — in the same call glued for the page's text and completed into
its reproduction-report row (:mod:`mechlib.reporting.report`) — and saves
``<records folder>/<notebook>.json`` (:func:`mechlib.paths.records_dir`). :func:`load` reads one
back. What the build does with records — compare them with ``tests/references``, update those,
check a cold re-run gives the same bytes — is the build wing's (:mod:`mechlib.pipeline`).
"""

from __future__ import annotations

import json
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from mechlib.blasinfo import openblas_kernel
from mechlib.params import check_float
from mechlib.paths import records_dir
from mechlib.reporting import claims, recordplan, report
from mechlib.reporting.jsonready import is_number as _is_number
from mechlib.reporting.jsonready import plain as _plain
from mechlib.reporting.recordhelpers import RecordHelpers

#: the record keys of claim verdicts: ``claims.<claim id>`` (see :meth:`Recorder.claim`)
CLAIM_PREFIX = "claims."
#: What a notebook may glue into its prose through :meth:`Recorder.value`: a name, or names
#: of elements of the recorded value by their index (``{"nu_x": 0, "nu_thx": 3}``).
Glue = str | Mapping[str, int | tuple[int, ...]]


#: the folder, under the records folder, of the data a notebook keeps for the bundle
DATA_DIR = "data"
#: each notebook's data folder's list of files and their descriptions
DATA_INDEX = "index.json"


def paste(name: str, value: Any) -> None:
    """Glue ``value`` under ``name`` for the notebook's prose (myst-nb, not displayed)."""
    from myst_nb import glue  # here: only notebooks paste, and myst-nb imports IPython

    glue(name, value, display=False)


@dataclass
class Recorder(RecordHelpers):
    """Collects the key numbers, the numbers quoted in the prose and the report rows of one
    notebook.

    One call, :meth:`value`, records a number with its tolerance, makes it (or some of its
    elements) available to the prose under a glue name, and adds the report row that compares
    it with the thesis: every number the book quotes is then checked against the committed
    references. Text that is not a number goes to the prose through :meth:`text`, which says
    what it is made from or why it is not checked. Shorthands: :meth:`mapping`, :meth:`skipped`.

    Parameters
    ----------
    notebook : str
        Notebook name without extension; the record file is ``<notebook>.json``.
    paste : callable, optional
        ``paste(name, value)`` glues a value for the prose; default :func:`paste` (myst-nb).
    registry : callable, optional
        ``registry(claim_id)`` gives the registered :class:`~mechlib.reporting.claims.ClaimSpec`
        that :meth:`claim` judges (the book's registry: :func:`mechlib.reporting.claimlist.claim`).
        Passed by the notebook, so that the recorder imports no science: the registry reads
        constants of the science packages, the recorder sits below them.
    plan : mapping of str to recordplan.Entry, optional
        The chapter's record plan (:mod:`mechlib.reporting.plans`): every key it records, with
        its tolerance, glue and report rows. With a plan, :meth:`value` takes the value alone
        (and ``context=`` for rows made from notebook values), refuses a key the plan does not
        hold, and :meth:`save` refuses a run that left a (not optional) key of it out. Without
        one (tests, scripts), :meth:`value` takes ``rtol``, ``atol``, ``glue`` and ``row``.
    about : mapping, optional
        The plan module's ``DATA``: each data file's one-line description, a str or
        ``about(context)``, for :meth:`add_data` (:func:`mechlib.reporting.plans.recorder`).
    timing_glue : mapping of str to str, optional
        The plan module's ``TIMINGS``: the glue name of a timing's key, for :meth:`timing`.
    unchecked : mapping of str to str, optional
        The plan module's ``UNCHECKED``: why the text glued under a name is not checked (a
        reason several texts share, such as a timing's, written once), for :meth:`text`.
    """

    notebook: str
    values: dict[str, dict[str, Any]] = field(default_factory=dict)
    report: list[dict[str, Any]] = field(default_factory=list)
    glued: dict[str, dict[str, Any]] = field(default_factory=dict)
    paste: Callable[[str, Any], None] = field(default=paste, repr=False)
    timings: dict[str, float] = field(default_factory=dict)
    data: dict[str, tuple[str, str]] = field(default_factory=dict)
    registry: Callable[[str], claims.ClaimSpec] | None = field(default=None, repr=False)
    plan: recordplan.Plan | None = field(default=None, repr=False)
    about: Mapping[str, str | Callable[[Mapping[str, Any]], str]] = field(default_factory=dict)
    timing_glue: Mapping[str, str] = field(default_factory=dict, repr=False)
    unchecked: Mapping[str, str] = field(default_factory=dict, repr=False)

    def __post_init__(self) -> None:
        if self.plan is not None:
            recordplan.check_plan(self.plan, self.notebook)

    def value(
        self,
        key: str,
        value: Any,
        *,
        rtol: float | None = None,
        atol: float | None = None,
        glue: Glue | None = None,
        row: report.RowSpec | Sequence[report.RowSpec] | None = None,
        context: Mapping[str, Any] | None = None,
    ) -> Any:
        """Record ``value`` under ``key`` with the tolerance a re-run must meet; glue it for the
        prose and add its report row(s). With a plan, all but the value come from the plan.

        Parameters
        ----------
        key : str
            Unique name, dotted by topic (``"table3.effects"``).
        value : float, int, bool, str or array_like
            The number(s). Arrays are stored as nested lists.
        rtol, atol : float
            Relative and absolute tolerance of numbers: ``|a - b| <= atol + rtol * |b|``. A
            number (int or float, scalar or array) needs at least one of them (``atol=0`` for
            exact); booleans and strings are compared exactly.
        glue : str or dict, optional
            Glue name of a scalar number, or ``{name: index}`` to glue elements of an array
            (as Python ``float``/``int``, what myst-nb formats).
        row : report.Comparison, report.Check, report.Computed or report.NotReproduced, or a list
            Report rows completed with this value (see :mod:`mechlib.reporting.report`).
        context : dict, optional
            With a plan: the notebook's values its entry's functions read, by name (they find
            the recorded value itself under ``"value"``: :mod:`~mechlib.reporting.recordplan`).

        Returns
        -------
        The value as given, so a record can be written inline.

        Raises
        ------
        ValueError
            A key or glue name used twice, a number without tolerance, a negative tolerance,
            a non-finite number, or a glued element that is not a number; with a plan, a key it
            does not hold, a tolerance, glue or row given here, or a context its entry does not
            read (or a missing one it does).
        """
        if self.plan is not None:
            named = {"rtol": rtol, "atol": atol, "glue": glue, "row": row}
            given = [name for name, v in named.items() if v is not None]
            if given:
                raise ValueError(
                    f"{key}: {self.notebook} records by its plan, which gives the tolerance, "
                    f"glue and rows: drop {', '.join(given)}= here"
                )
            recorded = {k: e["value"] for k, e in self.values.items()}
            got = recordplan.resolve(self.plan, key, value, context, self.notebook, recorded)
            rtol, atol, glue, row = got.tol.rtol, got.tol.atol_for(value), got.glue, got.rows
        elif context is not None:
            raise ValueError(f"{key}: context= is read by a plan; {self.notebook} has none")
        texts, text_of = (got.texts, got.text_of) if self.plan is not None else (None, None)
        return self._record(
            key, value, rtol=rtol, atol=atol, glue=glue, row=row, texts=texts, text_of=text_of
        )

    def _record(
        self,
        key: str,
        value: Any,
        *,
        rtol: float | None,
        atol: float | None,
        glue: Glue | None,
        row: report.RowSpec | Sequence[report.RowSpec] | None,
        texts: Mapping[str, str | float] | None = None,
        text_of: Mapping[str, str] | None = None,
    ) -> Any:
        """:meth:`value` once its tolerance, glue, rows and texts (made of it, or of the keys
        ``text_of`` gives by name) are known."""
        if key in self.values or key in self.timings:
            raise ValueError(f"record key {key!r} was already recorded in {self.notebook}")
        if _is_number(value) and rtol is None and atol is None:
            raise ValueError(
                f"{key}: a number is recorded with its tolerance: give rtol and/or atol "
                f"(atol=0 for an exact value)"
            )
        rtol = check_float("rtol", 0.0 if rtol is None else rtol, low=0.0)
        atol = check_float("atol", 0.0 if atol is None else atol, low=0.0)
        entry = {"value": _plain(value), "rtol": rtol, "atol": atol}
        for name, text in (texts or {}).items():
            self._check_text(name, text)
        pasted, glued = {}, {}
        for name, index in ({glue: ()} if isinstance(glue, str) else dict(glue or {})).items():
            item = np.asarray(value)[index]
            if item.ndim or not _is_number(item):
                raise ValueError(
                    f"{key}: glue {name!r} must name one number, got {item!r} (text goes "
                    f"through Recorder.text)"
                )
            self._check_name(name)
            pasted[name] = item.item()
            glued[name] = {"key": key, **({"index": _plain(index)} if index != () else {})}
        specs = [] if row is None else [row] if hasattr(row, "row") else list(row)
        rows = [{k: _plain(v) for k, v in s.row(value).items()} for s in specs]
        # nothing is kept before every check has passed
        self.values[key] = entry
        self.glued |= glued
        self.report += rows
        for name, item in pasted.items():
            self.paste(name, item)
        for name, text in (texts or {}).items():
            self.text(name, text, of=(text_of or {}).get(name, key))
        return value

    def text(self, name: str, text: str | float, *, of: str = "", why: str = "") -> str | float:
        """Glue a text that is not a recorded number (a label, a formatted list) for the prose.

        Parameters
        ----------
        name : str
            Glue name.
        text : str or float
            The text; NaN for a number this run does not compute.
        of : str
            The record key(s) the text is made from (comma-separated), recorded before.
        why : str
            Otherwise, why the text is not checked (e.g. a machine-dependent timing); by
            default the reason ``unchecked`` gives the name, if any.

        Raises
        ------
        ValueError
            A glue name used twice, neither or both of ``of`` and ``why`` (the plan's reason
            counts as ``why``), an ``of`` key not recorded, or a finite number (numbers go
            through :meth:`value`).
        """
        self._check_text(name, text)
        if name in self.unchecked:
            if of or why:
                raise ValueError(
                    f"text {name!r}: the plan's UNCHECKED says why it is not checked: drop "
                    f"{'of' if of else 'why'}= here"
                )
            why = self.unchecked[name]
        if bool(of) == bool(why):
            raise ValueError(f"text {name!r}: say what it is made of (of=) or why not (why=)")
        missing = [k.strip() for k in of.split(",") if of and k.strip() not in self.values]
        if missing:
            raise ValueError(f"text {name!r} is made of {missing}, which were not recorded")
        self.glued[name] = {"text_of": of} if of else {"unchecked": why}
        self.paste(name, text)
        return text

    def _check_text(self, name: str, text: Any) -> None:
        if not isinstance(text, str) and not (isinstance(text, float) and np.isnan(text)):
            raise ValueError(f"text {name!r} must be a str or NaN, got {text!r} (numbers: value)")
        self._check_name(name)

    def _check_name(self, name: str) -> None:
        if not name or name in self.glued:
            raise ValueError(f"glue name {name!r} is empty or was already used in {self.notebook}")

    def timing(self, key: str, value: float, *, glue: str | None = None) -> float:
        """Record a measured time (or a rate made from one) under ``key``: machine- and
        load-dependent, so it is kept in the record's ``timings``, which neither the references
        nor the determinism re-run compare; glued for the prose under ``glue``.

        Parameters
        ----------
        key : str
            Unique name among the record's values and timings.
        value : float
            The time (any unit the key names, e.g. ``_us``), finite and ≥ 0.
        glue : str, optional
            Glue name for the prose, without a plan; with one, the plan module's ``TIMINGS``
            give it (``timing_glue``).

        Returns
        -------
        float
            ``value``, checked.

        Raises
        ------
        ValueError
            A key already recorded (as a value or a timing), a glue name used twice or given
            here with a plan, or a value that is not a finite number ≥ 0.
        """
        if key in self.values or key in self.timings:
            raise ValueError(f"record key {key!r} was already recorded in {self.notebook}")
        if glue is not None and self.plan is not None:
            raise ValueError(
                f"timing {key!r}: {self.notebook} records by its plan: give its glue in the plan "
                f"module's TIMINGS, drop glue= here"
            )
        if glue is not None and key in self.timing_glue:
            raise ValueError(f"timing {key!r}: its glue is in the plan's TIMINGS: drop glue= here")
        glue = self.timing_glue.get(key, glue)
        value = check_float(key, value, low=0.0)
        if glue is not None:
            self._check_name(glue)
        self.timings[key] = value
        if glue is not None:
            self.glued[glue] = {"key": key, "timing": True}
            self.paste(glue, value)
        return value

    def claim(self, *claim_ids: str) -> str | list[str]:
        """Judge the registered claims ``claim_ids`` (looked up in ``registry``), in order, from
        this notebook's records: each verdict word is recorded under ``claims.<claim_id>`` and
        its report row added, as one call per claim would. Pages quote the word by id.

        Returns
        -------
        str or list of str
            The verdict word ("supported", "not supported", "mixed"; "holds", "does not hold"),
            or the list of them for several ids.

        Raises
        ------
        KeyError
            An id the registry does not hold, or a value its rule reads that was not recorded.
        ValueError
            No id, a claim whose evidence another notebook records, one judged twice, or a
            recorder made without a registry.
        """
        if self.registry is None or not claim_ids:
            raise ValueError(
                f"claims: {self.notebook} judges claims {claim_ids} by id with a registry: make "
                f"the Recorder as Recorder(name, registry=claimlist.claim), name at least one id"
            )
        words = []
        for claim_id in claim_ids:
            spec = self.registry(claim_id)
            if spec.page != self.notebook:
                raise ValueError(
                    f"claim {claim_id!r} is judged on {spec.page}, not {self.notebook}"
                )
            verdict = claims.evaluate(spec, {**self.values, **self.timings})
            # a claim's key is its registry entry's, not the plan's
            key = f"{CLAIM_PREFIX}{claim_id}"
            self._record(key, verdict.word, rtol=None, atol=None, glue=None, row=None)
            self.report.append({k: _plain(v) for k, v in verdict.row().items()})
            words.append(verdict.word)
        return words[0] if len(words) == 1 else words

    def save(self, folder: Path | None = None) -> Path:
        """Write ``<folder>/<notebook>.json`` deterministically and return its path; the data
        kept by :meth:`add_data` go to ``<folder>/data/<notebook>/`` with an ``index.json``.

        Raises
        ------
        ValueError
            With a plan, naming the keys of the plan (not optional) that were not recorded.
        """
        missing = recordplan.unrecorded(self.plan, set(self.values)) if self.plan else []
        if missing:
            raise ValueError(
                f"{self.notebook}: keys of its plan were not recorded: {', '.join(missing)} "
                f"(record them, mark them optional=True, or drop them from the plan)"
            )
        folder = Path(folder) if folder is not None else records_dir()
        folder.mkdir(parents=True, exist_ok=True)
        path = folder / f"{self.notebook}.json"
        payload = {
            "notebook": self.notebook,
            "values": self.values,
            "report": self.report,
            "glue": self.glued,
            # the BLAS kernel the values were computed with: references come from the machine's
            # own, `make test` compares them with another's (mechlib.pipeline.kernels)
            "blas": openblas_kernel(),
        }
        if self.timings:  # machine-dependent: not compared (see :meth:`timing`)
            payload["timings"] = self.timings
        path.write_text(json.dumps(payload, indent=1, sort_keys=True) + "\n")
        if self.data:
            data_dir = folder / DATA_DIR / self.notebook
            data_dir.mkdir(parents=True, exist_ok=True)
            for file, (text, _) in self.data.items():
                (data_dir / file).write_text(text)
            index = {file: about for file, (_, about) in self.data.items()}
            (data_dir / DATA_INDEX).write_text(json.dumps(index, indent=1, ensure_ascii=False))
        return path


def load(path: Path) -> dict[str, Any]:
    """Read one record or reference file."""
    return json.loads(Path(path).read_text())

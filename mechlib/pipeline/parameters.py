"""A notebook's parameters and the papermill arguments that set them.

:func:`notebook_parameters` reads the names a notebook's ``parameters`` cell defines;
:func:`given_parameters` reads the names papermill arguments set (``-p``, ``-r``, ``-y``, ``-f``,
``-b`` in every form papermill takes); :func:`check_parameter_names` refuses a name the notebook
does not define (papermill itself only warns and runs the defaults).
"""

from __future__ import annotations

import ast
import base64
import binascii
import difflib
import json
from collections.abc import Sequence
from pathlib import Path

import yaml

#: papermill's options that set notebook parameters, and how many values each takes.
PARAMETER_OPTIONS: dict[str, int] = {
    "-p": 2,
    "--parameters": 2,
    "-r": 2,
    "--parameters_raw": 2,
    "-y": 1,
    "--parameters_yaml": 1,
    "-f": 1,
    "--parameters_file": 1,
    "-b": 1,
    "--parameters_base64": 1,
}
#: Tag of the cell whose assignments are a notebook's parameters (papermill's convention).
PARAMETERS_TAG = "parameters"


def _yaml_names(option: str, text: str | bytes) -> list[str]:
    """Top-level names of a YAML mapping given to ``option`` (empty YAML: none)."""
    try:
        data = yaml.safe_load(text)
    except yaml.YAMLError as err:
        why = getattr(err, "problem", None) or type(err).__name__
        raise ValueError(f"{option} must give a YAML mapping, got {text!r} ({why})") from None
    if data is None:
        return []
    if not isinstance(data, dict):
        raise ValueError(
            f"{option} must give a YAML mapping of parameter names to values, got {text!r}"
        )
    return [str(k) for k in data]


def _option_values(args: Sequence[str]) -> list[tuple[str, list[str]]]:
    """Each parameter option in ``args`` with its values, in the forms papermill (click) takes.

    ``-p name value``, ``-pname value`` (short option with its first value attached),
    ``--parameters_yaml=text`` (long single-value option with ``=``); other arguments are
    skipped.
    """
    found, i = [], 0
    while i < len(args):
        token = args[i]
        head, eq, tail = token.partition("=")
        if token in PARAMETER_OPTIONS:
            option, values, i = token, [], i + 1
        elif token.startswith("--") and eq and PARAMETER_OPTIONS.get(head) == 1:
            option, values, i = head, [tail], i + 1
        elif not token.startswith("--") and token[:2] in PARAMETER_OPTIONS and len(token) > 2:
            option, values, i = token[:2], [token[2:]], i + 1
        else:
            i += 1
            continue
        need = PARAMETER_OPTIONS[option] - len(values)
        values += list(args[i : i + need])
        if len(values) < PARAMETER_OPTIONS[option]:
            what = "a name and a value" if PARAMETER_OPTIONS[option] == 2 else "a value"
            raise ValueError(f"{option} needs {what}, got {list(args[i - 1 :])}")
        found.append((option, values))
        i += need
    return found


def given_parameters(args: Sequence[str]) -> list[str]:
    """Names of the notebook parameters that papermill arguments set, in the order given.

    Parameters
    ----------
    args : sequence of str
        papermill arguments: ``-p``/``--parameters`` and ``-r``/``--parameters_raw`` name and
        value, ``-y``/``--parameters_yaml`` YAML text, ``-f``/``--parameters_file`` a YAML file
        (read here), ``-b``/``--parameters_base64`` base64-encoded YAML; other arguments are
        ignored.

    Returns
    -------
    list of str

    Raises
    ------
    ValueError
        If an option lacks its values, a YAML value is not a mapping, a parameters file cannot
        be read, or a base64 value does not decode.
    """
    names: list[str] = []
    for option, values in _option_values(args):
        if PARAMETER_OPTIONS[option] == 2:
            names.append(values[0])
        elif option in ("-f", "--parameters_file"):
            try:
                text = Path(values[0]).read_text()
            except OSError as err:
                raise ValueError(f"{option} {values[0]}: cannot read the file ({err})") from None
            names += _yaml_names(f"{option} {values[0]}", text)
        elif option in ("-b", "--parameters_base64"):
            try:
                text = base64.b64decode(values[0], validate=True)
            except (binascii.Error, ValueError):
                raise ValueError(
                    f"{option} must be base64-encoded YAML, got {values[0]!r}"
                ) from None
            names += _yaml_names(option, text)
        else:
            names += _yaml_names(option, values[0])
    return names


def check_parameter_names(
    args: Sequence[str], allowed: Sequence[str], notebook: str = "the notebook"
) -> list[str]:
    """Names set by papermill ``args``, refusing any that ``allowed`` does not list.

    Parameters
    ----------
    args : sequence of str
        papermill arguments (see :func:`given_parameters`).
    allowed : sequence of str
        The notebook's parameter names (:func:`notebook_parameters`).
    notebook : str
        How to name the notebook in the message.

    Returns
    -------
    list of str
        The given names.

    Raises
    ------
    ValueError
        Naming each unknown parameter (with the closest allowed name, if one is close) and
        listing the allowed ones.
    """
    given = given_parameters(args)
    unknown = [n for n in dict.fromkeys(given) if n not in allowed]
    if unknown:
        described = []
        for name in unknown:
            close = difflib.get_close_matches(name, list(allowed), n=1)
            described.append(f"{name!r}" + (f" (did you mean {close[0]!r}?)" if close else ""))
        raise ValueError(
            f"unknown parameter {', '.join(described)} for {notebook}: its parameters cell "
            f"defines {', '.join(allowed) if allowed else 'none'}"
        )
    return given


def parameters_cell_names(source: str) -> list[str]:
    """Names assigned at the top level of a parameters cell's source, in order."""
    names: list[str] = []
    for node in ast.parse(source).body:
        targets = node.targets if isinstance(node, ast.Assign) else []
        if isinstance(node, ast.AnnAssign):
            targets = [node.target]
        for target in targets:
            elts = target.elts if isinstance(target, (ast.Tuple, ast.List)) else [target]
            names += [e.id for e in elts if isinstance(e, ast.Name)]
    return list(dict.fromkeys(names))


def notebook_parameters(path: Path) -> list[str]:
    """Parameter names of a notebook: the assignments of its cell tagged ``parameters``.

    Read with Python's own parser rather than ``papermill.inspect_notebook``, which skips any
    line holding a second ``=`` (in a comment, say: hexflex_model's ``tab_half_width``).

    Raises
    ------
    ValueError
        If the parameters cell is not valid Python.
    """
    nb = json.loads(Path(path).read_text())
    for cell in nb.get("cells", []):
        if PARAMETERS_TAG in cell.get("metadata", {}).get("tags", []):
            source = cell.get("source", "")
            source = "".join(source) if isinstance(source, list) else source
            try:
                return parameters_cell_names(source)
            except SyntaxError as err:
                raise ValueError(f"the parameters cell of {path} is not Python: {err}") from None
    return []

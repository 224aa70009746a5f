"""MATLAB v7.3 MAT-files (HDF5) read as ``scipy.io.loadmat`` reads the earlier versions.

MATLAB has saved in HDF5 since version 7.3 (the default for files over 2 GB and in many
sites' settings); scipy reads versions 4 to 7 only. A v7.3 file holds each variable as an
HDF5 dataset whose ``MATLAB_class`` attribute names its class, stored in MATLAB's column-major
order (an N x 1 column as 1 x N), and each struct as a group of its fields. This module gives
what ``loadmat(path, squeeze_me=True, struct_as_record=False)`` gives for a v7 file: arrays
in MATLAB's orientation with their unit dimensions squeezed, character arrays as ``str``,
structs as objects whose fields are attributes named in ``_fieldnames``, cells as object
arrays. The HDF5 is read by h5py.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

__all__ = ["MatStruct", "read_mat_v73"]

#: The classes of numeric MATLAB arrays (read as numbers).
NUMERIC_CLASSES = frozenset(
    {
        "double",
        "single",
        "int8",
        "uint8",
        "int16",
        "uint16",
        "int32",
        "uint32",
        "int64",
        "uint64",
    }
)


class MatStruct:
    """A MATLAB struct: its fields as attributes, their names in ``_fieldnames``.

    The interface of ``scipy.io.matlab.mat_struct`` (``struct_as_record=False``).

    Parameters
    ----------
    fields : dict of str to Any
        Field name -> value.
    """

    def __init__(self, fields: dict[str, Any]) -> None:
        self._fieldnames = list(fields)
        for name, value in fields.items():
            setattr(self, name, value)

    def __repr__(self) -> str:
        return f"MatStruct({', '.join(self._fieldnames)})"


def _class_of(node: Any) -> str:
    value = node.attrs.get("MATLAB_class", b"")
    return value.decode("ascii", "replace") if isinstance(value, bytes) else str(value)


def _squeezed(array: np.ndarray) -> Any:
    """MATLAB's orientation (the stored axes reversed), unit dimensions squeezed."""
    array = np.squeeze(np.asarray(array).T)
    return array[()] if array.ndim == 0 else array


def _value(node: Any, file: Any) -> Any:
    import h5py

    matlab_class = _class_of(node)
    if isinstance(node, h5py.Group):
        fields = {k: _value(node[k], file) for k in node if not k.startswith("#")}
        return MatStruct(fields)
    if node.attrs.get("MATLAB_empty", 0):
        return np.empty(0, dtype=float if matlab_class in NUMERIC_CLASSES else object)
    data = node[()]
    if node.dtype.kind == "O" or h5py.check_dtype(ref=node.dtype) is not None:
        # a cell, or a field of a struct array: references to the elements' values
        refs = np.asarray(data)
        values = np.empty(refs.shape, dtype=object)
        for index, ref in np.ndenumerate(refs):
            values[index] = _value(file[ref], file) if ref else None
        out = _squeezed(values)
        return out
    if node.dtype.names and {"real", "imag"} <= set(node.dtype.names):
        data = np.asarray(data["real"]) + 1j * np.asarray(data["imag"])
    if matlab_class == "char":
        return "".join(chr(int(c)) for c in np.asarray(data).T.ravel())
    if matlab_class == "logical":
        return _squeezed(np.asarray(data, dtype=bool))
    return _squeezed(data)


def read_mat_v73(path: str | Path) -> dict[str, Any]:
    """The variables of a MATLAB v7.3 MAT-file.

    Parameters
    ----------
    path : str or pathlib.Path
        The file.

    Returns
    -------
    dict of str to Any
        Variable name -> value: numeric arrays in MATLAB's orientation, unit dimensions
        squeezed (a scalar as a numpy scalar), text as ``str``, structs as
        :class:`MatStruct`, cells as object arrays; MATLAB's own groups (``#refs#``,
        ``#subsystem#``) left out.

    Raises
    ------
    OSError
        The file is not HDF5 or cannot be read (h5py's error).
    """
    import h5py

    with h5py.File(path, "r") as file:
        return {name: _value(file[name], file) for name in file if not name.startswith("#")}

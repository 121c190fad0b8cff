#!/usr/bin/env python3
"""NumPy's own .npy and .npz files for tests/interchange, generated ONCE with
numpy and checked in, so the readers are held to what numpy really writes
(np.savez's zip64 members, Fortran order, format versions 2.0 and 3.0).

    python3 tests/reference/generate_numpy_references.py

Every array is built from M = [[1.5, -2, 3e-9], [4, 5, 6.25]] (or its
integer or boolean form), so the tests know the values without numpy.
"""
import os
import pickle

import numpy as np

HERE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "numpy")
M = np.array([[1.5, -2, 3e-9], [4, 5, 6.25]])
I = np.array([[1, -2, 3], [4, 5, -32768]])


def path(name):
    return os.path.join(HERE, name)


def main():
    os.makedirs(HERE, exist_ok=True)
    np.save(path("m_f8.npy"), M)
    np.save(path("m_f8_fortran_be.npy"), np.asfortranarray(M.astype(">f8")))
    np.save(path("i_i2_be.npy"), I.astype(">i2"))
    np.save(path("i_u1_fortran.npy"), np.asfortranarray(np.abs(I[:, :2]).astype("u1")))
    np.save(path("b_bool.npy"), M > 1)
    with open(path("m_f4_v2.npy"), "wb") as f:
        np.lib.format.write_array(f, M.astype("<f4"), version=(2, 0))
    with open(path("m_i8_v3.npy"), "wb") as f:
        np.lib.format.write_array(f, I.astype("<i8"), version=(3, 0))
    np.save(path("row_f8.npy"), M[1])
    np.savez(path("two.npz"), data=M, t=np.array([0.0, 0.5, 1.0]))
    np.savez_compressed(path("two_compressed.npz"), data=M, t=np.array([0.0, 0.5, 1.0]))
    np.save(path("object.npy"), np.array([{"torque": 1}], dtype=object), allow_pickle=True)
    with open(path("pickle.npy"), "wb") as f:
        pickle.dump([1.0, 2.0], f, protocol=4)


if __name__ == "__main__":
    main()

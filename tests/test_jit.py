"""fewear.jit: the compile cache's state, as the wear run announces a first compile."""

import numba

from fewear.jit import holds_compiled_code
from fewear.kernels import compile_kernels


def test_an_empty_cache_holds_no_compiled_code_and_an_index_file_does(tmp_path):
    assert not holds_compiled_code(str(tmp_path))
    assert not holds_compiled_code(str(tmp_path / "missing"))
    (tmp_path / "fewear" / "contact").mkdir(parents=True)
    (tmp_path / "fewear" / "contact" / "newton.norm-245.py311.nbi").write_bytes(b"index")
    assert holds_compiled_code(str(tmp_path))


def test_a_warm_cache_compiles_without_a_word():
    """The suite's processes run on a filled cache (earlier tests compiled the kernels): no
    announcement of a minute's compile."""
    compile_kernels()
    said = []
    compile_kernels(said.append)
    assert holds_compiled_code(numba.config.CACHE_DIR) and said == []

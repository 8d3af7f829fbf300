"""Write failures become one-line errors that name the file and say why in words."""

from __future__ import annotations

import errno
import os

from mjcfbuild.errors import EXIT_OUTPUT, OutputError, write_failure


def test_a_full_disk_names_the_file_and_says_so():
    error = write_failure(OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), "/out/model.xml"))
    assert isinstance(error, OutputError) and error.exit_code == EXIT_OUTPUT
    assert error.one_line().startswith("/out/model.xml: cannot write: no space left on the device")


def test_the_file_given_wins_over_the_errors_own():
    error = write_failure(OSError(errno.EDQUOT, "quota", "/tmp/x.tmp"), file="mjcf/doit.sqlite3")
    assert error is not None
    assert error.one_line().startswith("mjcf/doit.sqlite3: cannot write: disk quota exceeded")


def test_permission_denied_and_read_only_in_words(tmp_path):
    for code, words in ((errno.EACCES, "permission denied"), (errno.EROFS, "read-only file")):
        error = write_failure(OSError(code, os.strerror(code), str(tmp_path / "new.png")))
        assert isinstance(error, OutputError) and words in error.one_line()


def test_other_errors_are_not_write_failures():
    assert write_failure(OSError(errno.ENOENT, "No such file", "/x")) is None
    assert write_failure(ValueError("no")) is None
    assert write_failure(OSError("no errno")) is None

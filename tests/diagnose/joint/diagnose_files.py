"""`fewear diagnose` on the files of a generated joint data set (any generator's ``DataSet`` with
``believed_toml``, ``profiles_csv`` and ``max_wear_csv``), as the command runs it."""


def diagnose_data_set(data) -> dict:
    """The diagnosis summary (the keys of ``diagnosis.json``) of ``data`` against its believed
    config."""
    from fewear.diagnose.joint.diagnose import diagnose_joint
    from fewear.diagnose.joint.measured import read_joint_measurements
    from fewear.diagnose.joint.report import summarise
    from fewear.io.config import load_config
    from fewear.loop.settings import run_sections

    config = load_config(data.believed_toml, run_sections())
    measured = read_joint_measurements([data.profiles_csv, data.max_wear_csv])
    return summarise(diagnose_joint(measured, config))


def missed(cause: str, reason: str):
    """A cause of a generator's slow tests that the diagnosis misses, as measured (``reason``):
    a strict xfail, so a change that fixes it is seen."""
    import pytest

    return pytest.param(cause, marks=pytest.mark.xfail(strict=True, reason=reason))


def assert_names_the_hidden_cause(generator, cause: str, folder) -> None:
    """The first data set of ``cause`` from ``generator`` (a module with ``write_data_set`` and
    ``data_set_seed``): the hidden cause is the one named, and its extended run predicts the
    held-out profiles better than the believed model."""
    data = generator.write_data_set(cause, generator.data_set_seed(cause, 0), folder)
    summary = diagnose_data_set(data)
    print(f"{cause}: truth {data.params}; named {summary['causes'] or ['none']}, gain "
          f"{summary['gain']:+.2f}, unexplained {summary['unexplained']}")
    assert summary["cause"] == cause, (data.params, summary["causes"])
    assert summary["gain"] > 0.0

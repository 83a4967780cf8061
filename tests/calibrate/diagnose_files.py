"""`fewear diagnose` on the files of a generated joint data set (any generator's ``DataSet`` with
``believed_toml``, ``profiles_csv`` and ``max_wear_csv``), as the command runs it."""


def diagnose_data_set(data) -> dict:
    """The diagnosis summary (the keys of ``diagnosis.json``) of ``data`` against its believed
    config."""
    from fewear.calibrate.joint_diagnose import diagnose_joint
    from fewear.calibrate.joint_measured import read_joint_measurements
    from fewear.io.config import load_config
    from fewear.pipeline import run_sections

    config = load_config(data.believed_toml, run_sections())
    measured = read_joint_measurements([data.profiles_csv, data.max_wear_csv])
    return diagnose_joint(measured, config).summary

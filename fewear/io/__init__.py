"""Configuration files and command outputs."""

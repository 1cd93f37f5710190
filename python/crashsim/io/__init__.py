"""Files in and out: TOML scene files with units, the animated GLB export."""

"""The diagnosis of wear measured on the joint (bore profiles, maximum-depth growth, traces)
against the config the user believes, through forward runs of the wear loop."""

"""One module per ``symtmm`` subcommand (discovered by :mod:`symtmm.cli`)."""

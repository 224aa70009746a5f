"""The ``cmtool`` subcommands, one function ``cmd_<name>(args) -> exit code`` each.

:mod:`cmtool.cli` builds the parser and dispatches; these modules do the work.
"""

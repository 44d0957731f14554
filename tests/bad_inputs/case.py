"""One catalogue entry: the command, its input files and what must happen."""


class Case:
    """A bad input and the expected refusal.

    name     unique, "<area>/<what>", used as the filter on the command line
    args     the command after the binary; {assets} is the assets folder, {dir} the case's folder
    files    {relative name: str or bytes}, or a function of the assets folder returning that
    expect   fragments standard error must hold (the file or option, the place, the expectation)
    outputs  paths, relative to the case's folder, that must not exist afterwards
    folders  empty folders to create
    code     the expected exit code
    pending  why the case cannot pass yet (work of another branch), or None
    """

    def __init__(self, name, args, expect, files=None, outputs=(), folders=(), code=2,
                 pending=None):
        self.name = name
        self.args = list(args)
        self.expect = list(expect)
        self._files = files or {}
        self.outputs = list(outputs)
        self.folders = list(folders)
        self.code = code
        self.pending = pending

    def files(self, assets):
        return self._files(assets) if callable(self._files) else self._files


def read_asset(assets, name, mode="r"):
    with open("%s/%s" % (assets, name), mode) as f:
        return f.read()

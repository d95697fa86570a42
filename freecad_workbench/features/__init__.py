"""App-side proxies of Tessella's document objects (no GUI imports here).

The module paths below this package are stored in saved .FCStd files: never move
or rename them.
"""

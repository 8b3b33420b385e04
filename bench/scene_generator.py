# The reference scenes' generator loaded as a module, for the scripts that add
# scenes of their own to it (bench/own_scenes.py, tests/blender/glossy_scenes.py):
# its functions as they are, its main() not run.
#   gen = scene_generator.load()   # from: blender -b --python SCRIPT -- GENERATOR [its arguments]
import os, sys


def load():
    """The generator named first after '--', its namespace as a dict; the arguments after it are
    left for the generator's own parser."""
    argv = sys.argv[sys.argv.index('--') + 1:]
    generator = argv[0]
    sys.argv = [sys.argv[0], '--'] + argv[1:]  # the generator reads its own arguments after '--'
    gen = {'__file__': os.path.abspath(generator), '__name__': 'make_scenes'}
    source = open(generator).read()
    exec(compile(source[:source.rindex('\nmain()')], generator, 'exec'), gen)
    return gen

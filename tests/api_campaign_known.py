"""Known failures of the bad-input campaign (tests/test_api_campaign.py), as strict xfails.

``"module.callable:parameter"`` -> (what fails, slow): each call listed fails today (written by
``python tests/api_campaign_record.py`` from a run of the campaign, then read). Fix them and delete
the entry (strict: a fixed entry turns the run red until it is deleted). ``slow`` marks an entry
whose calls hang until the campaign's 10 s alarm. ``"module.callable:*"`` is the hypothesis search
over random numbers for that callable (its first failing example).
"""

KNOWN = {
    'cantilever.Cantilever.from_material:material': ((
        'cantilever.Cantilever.from_material(material=list) -> TypeError not naming material: '
        '"unhashable type: \'list\'"\n'
        'cantilever.Cantilever.from_material(material=2d) -> TypeError not naming material: "u'
        'nhashable type: \'numpy.ndarray\'"\n'
        'cantilever.Cantilever.from_material(material=empty) -> TypeError not naming material:'
        ' "unhashable type: \'numpy.ndarray\'"\n'
        'cantilever.Cantilever.from_material(material=nan-array) -> TypeError not naming mater'
        'ial: "unhashable type: \'numpy.ndarray\'"'
    ), False),
    'cantilever.Cantilever.mode_shape:mode': ((
        'cantilever.Cantilever.mode_shape(mode=list) -> TypeError not naming mode: "unhashable'
        ' type: \'list\'"\n'
        'cantilever.Cantilever.mode_shape(mode=2d) -> TypeError not naming mode: "unhashable t'
        'ype: \'numpy.ndarray\'"\n'
        'cantilever.Cantilever.mode_shape(mode=empty) -> TypeError not naming mode: "unhashabl'
        'e type: \'numpy.ndarray\'"\n'
        'cantilever.Cantilever.mode_shape(mode=nan-array) -> TypeError not naming mode: "unhas'
        'hable type: \'numpy.ndarray\'"'
    ), False),
    'cantilever.Cantilever.resonance_frequency:mode': ((
        'cantilever.Cantilever.resonance_frequency(mode=list) -> TypeError not naming mode: "u'
        'nhashable type: \'list\'"\n'
        'cantilever.Cantilever.resonance_frequency(mode=2d) -> TypeError not naming mode: "unh'
        'ashable type: \'numpy.ndarray\'"\n'
        'cantilever.Cantilever.resonance_frequency(mode=empty) -> TypeError not naming mode: "'
        'unhashable type: \'numpy.ndarray\'"\n'
        'cantilever.Cantilever.resonance_frequency(mode=nan-array) -> TypeError not naming mod'
        'e: "unhashable type: \'numpy.ndarray\'"'
    ), False),
    'cantilever.Cantilever.strain:z_b': ((
        "cantilever.Cantilever.strain(z_b=empty) -> ValueError not naming z_b: 'operands could"
        " not be broadcast together with shapes (0,) (11,) '"
    ), False),
    'cantilever.Cantilever.stress:force': ((
        'cantilever.Cantilever.stress(force=huge) -> returned non-finite (array with 11 non-fi'
        'nite of 11)\n'
        'cantilever.Cantilever.stress(force=-huge) -> returned non-finite (array with 11 non-f'
        'inite of 11)'
    ), False),
    'cantilever.Cantilever.stress:z_b': ((
        "cantilever.Cantilever.stress(z_b=empty) -> ValueError not naming z_b: 'operands could"
        " not be broadcast together with shapes (0,) (11,) '"
    ), False),
    'cantilever.Cantilever:*': ((
        'cantilever.Cantilever(thickness=1e+202) -> OverflowError: "(34, \'Numerical result'
        ' out of range\')"'
    ), False),
    'cantilever.Cantilever:density': ((
        'cantilever.Cantilever(density=tiny) -> OverflowError: "(34, \'Numerical result out'
        ' of range\')"'
    ), False),
    'cantilever.Cantilever:length': ((
        'cantilever.Cantilever(length=huge) -> OverflowError: "(34, \'Numerical result out '
        'of range\')"\n'
        "cantilever.Cantilever(length=tiny) -> ZeroDivisionError: 'float division by zero'"
    ), False),
    'cantilever.Cantilever:thickness': ((
        'cantilever.Cantilever(thickness=huge) -> OverflowError: "(34, \'Numerical result o'
        'ut of range\')"\n'
        "cantilever.Cantilever(thickness=tiny) -> ZeroDivisionError: 'float division by zero'"
    ), False),
    'contact.Conical.force:z_s': ((
        'contact.Conical.force(z_s=huge) -> returned non-finite (inf)'
    ), False),
    'contact.Conical.profile:r': ((
        'contact.Conical.profile(r=nan) -> accepted silently\n'
        'contact.Conical.profile(r=str) -> accepted silently\n'
        'contact.Conical.profile(r=bool) -> accepted silently\n'
        'contact.Conical.profile(r=nan-array) -> accepted silently'
    ), False),
    'contact.ForceCurve:force': ((
        'contact.ForceCurve(force=nan) -> accepted silently\n'
        'contact.ForceCurve(force=str) -> accepted silently\n'
        'contact.ForceCurve(force=bool) -> accepted silently\n'
        'contact.ForceCurve(force=complex) -> accepted silently\n'
        'contact.ForceCurve(force=object) -> accepted silently\n'
        'contact.ForceCurve(force=nan-array) -> accepted silently'
    ), False),
    'contact.ForceCurve:name': ((
        'contact.ForceCurve(name=nan) -> accepted silently\n'
        'contact.ForceCurve(name=bool) -> accepted silently\n'
        'contact.ForceCurve(name=complex) -> accepted silently\n'
        'contact.ForceCurve(name=object) -> accepted silently\n'
        'contact.ForceCurve(name=nan-array) -> accepted silently'
    ), False),
    'contact.ForceCurve:spring_constant': ((
        'contact.ForceCurve(spring_constant=nan) -> accepted silently\n'
        'contact.ForceCurve(spring_constant=str) -> accepted silently\n'
        'contact.ForceCurve(spring_constant=bool) -> accepted silently\n'
        'contact.ForceCurve(spring_constant=complex) -> accepted silently\n'
        'contact.ForceCurve(spring_constant=object) -> accepted silently\n'
        'contact.ForceCurve(spring_constant=nan-array) -> accepted silently'
    ), False),
    'contact.ForceCurve:z_np': ((
        'contact.ForceCurve(z_np=nan) -> accepted silently\n'
        'contact.ForceCurve(z_np=str) -> accepted silently\n'
        'contact.ForceCurve(z_np=bool) -> accepted silently\n'
        'contact.ForceCurve(z_np=complex) -> accepted silently\n'
        'contact.ForceCurve(z_np=object) -> accepted silently\n'
        'contact.ForceCurve(z_np=nan-array) -> accepted silently'
    ), False),
    'contact.Parabolic.depth_for_radius:contact_radius': ((
        'contact.Parabolic.depth_for_radius(contact_radius=huge) -> returned non-finite (inf)'
    ), False),
    'contact.Parabolic.force:z_s': ((
        'contact.Parabolic.force(z_s=huge) -> returned non-finite (inf)'
    ), False),
    'contact.Parabolic.profile:r': ((
        'contact.Parabolic.profile(r=nan) -> accepted silently\n'
        'contact.Parabolic.profile(r=str) -> accepted silently\n'
        'contact.Parabolic.profile(r=bool) -> accepted silently\n'
        'contact.Parabolic.profile(r=huge) -> returned non-finite (np.float64(inf))\n'
        'contact.Parabolic.profile(r=-huge) -> returned non-finite (np.float64(inf))\n'
        'contact.Parabolic.profile(r=nan-array) -> accepted silently'
    ), False),
    'contact.Pyramidal.force:z_s': ((
        'contact.Pyramidal.force(z_s=huge) -> returned non-finite (inf)'
    ), False),
    'contact.Pyramidal.profile:r': ((
        'contact.Pyramidal.profile(r=nan) -> accepted silently\n'
        'contact.Pyramidal.profile(r=str) -> accepted silently\n'
        'contact.Pyramidal.profile(r=bool) -> accepted silently\n'
        'contact.Pyramidal.profile(r=nan-array) -> accepted silently'
    ), False),
    'contact.Spherical.max_z_np:*': ((
        "contact.Spherical.max_z_np(spring_constant=0.0) -> ZeroDivisionError: 'float division"
        " by zero'"
    ), False),
    'contact.Spherical.max_z_np:reduced_modulus': ((
        'contact.Spherical.max_z_np(reduced_modulus=nan) -> accepted silently\n'
        'contact.Spherical.max_z_np(reduced_modulus=str) -> TypeError not naming reduced_modul'
        'us: "can\'t multiply sequence by non-int of type \'float\'"\n'
        'contact.Spherical.max_z_np(reduced_modulus=bool) -> accepted silently\n'
        'contact.Spherical.max_z_np(reduced_modulus=complex) -> accepted silently\n'
        'contact.Spherical.max_z_np(reduced_modulus=list) -> TypeError not naming reduced_modu'
        'lus: "can\'t multiply sequence by non-int of type \'float\'"\n'
        'contact.Spherical.max_z_np(reduced_modulus=object) -> TypeError not naming reduced_mo'
        'dulus: "unsupported operand type(s) for *: \'Foreign\' and \'float\'"\n'
        'contact.Spherical.max_z_np(reduced_modulus=nan-array) -> accepted silently'
    ), False),
    'contact.Spherical.max_z_np:spring_constant': ((
        'contact.Spherical.max_z_np(spring_constant=nan) -> accepted silently\n'
        'contact.Spherical.max_z_np(spring_constant=str) -> TypeError not naming spring_consta'
        'nt: "unsupported operand type(s) for /: \'float\' and \'str\'"\n'
        'contact.Spherical.max_z_np(spring_constant=bool) -> accepted silently\n'
        'contact.Spherical.max_z_np(spring_constant=complex) -> accepted silently\n'
        'contact.Spherical.max_z_np(spring_constant=list) -> TypeError not naming spring_const'
        'ant: "unsupported operand type(s) for /: \'float\' and \'list\'"\n'
        'contact.Spherical.max_z_np(spring_constant=object) -> TypeError not naming spring_con'
        'stant: "unsupported operand type(s) for /: \'float\' and \'Foreign\'"\n'
        "contact.Spherical.max_z_np(spring_constant=zero) -> ZeroDivisionError: 'float divisio"
        "n by zero'\n"
        'contact.Spherical.max_z_np(spring_constant=nan-array) -> accepted silently'
    ), False),
    'contact.Spherical.profile:*': ((
        'contact.Spherical.profile(r=-4.801320636955862e-08) -> returned non-finite (np.float6'
        '4(nan))'
    ), False),
    'contact.Spherical.profile:r': ((
        'contact.Spherical.profile(r=nan) -> accepted silently\n'
        'contact.Spherical.profile(r=-inf) -> returned non-finite (np.float64(nan))\n'
        'contact.Spherical.profile(r=str) -> accepted silently\n'
        'contact.Spherical.profile(r=bool) -> accepted silently\n'
        'contact.Spherical.profile(r=negative) -> returned non-finite (np.float64(nan))\n'
        'contact.Spherical.profile(r=-huge) -> returned non-finite (np.float64(nan))\n'
        'contact.Spherical.profile(r=nan-array) -> accepted silently'
    ), False),
    'contact.Spherical:radius': ((
        'contact.Spherical(radius=huge) -> OverflowError: "(34, \'Numerical result out of r'
        'ange\')"'
    ), False),
    'contact.StandardLinearSolid:*': ((
        'contact.StandardLinearSolid(relaxed_modulus=1e+244) -> ValueError not naming relaxed_'
        "modulus: 'instantaneous_modulus must be in [1e+244, inf) Pa, got 2e+06'...'"
    ), False),
    'contact.StandardLinearSolid:relaxed_modulus': ((
        'contact.StandardLinearSolid(relaxed_modulus=huge) -> ValueError not naming relaxed_mo'
        "dulus: 'instantaneous_modulus must be in [1e+300, inf) Pa, got 2e+06'...'\n"
        'contact.StandardLinearSolid(relaxed_modulus=bigint) -> ValueError not naming relaxed_'
        "modulus: 'instantaneous_modulus must be in [1e+09, inf) Pa, got 2e+06'...'"
    ), False),
    'contact.approach_retract:work_of_adhesion': ((
        'contact.approach_retract(work_of_adhesion=nan) -> accepted silently\n'
        'contact.approach_retract(work_of_adhesion=None) -> accepted silently\n'
        'contact.approach_retract(work_of_adhesion=str) -> accepted silently\n'
        'contact.approach_retract(work_of_adhesion=bool) -> accepted silently\n'
        'contact.approach_retract(work_of_adhesion=complex) -> accepted silently\n'
        'contact.approach_retract(work_of_adhesion=object) -> accepted silently\n'
        'contact.approach_retract(work_of_adhesion=nan-array) -> accepted silently'
    ), False),
    'contact.approach_retract[jkr]:work_of_adhesion': ((
        'contact.approach_retract[jkr](work_of_adhesion=huge) -> ValueError not naming work_of'
        "_adhesion: 'The function value at x=0.0 is NaN; solver cannot continue.'...'"
    ), False),
    'contact.approach_retract[sphere-jkr]:work_of_adhesion': ((
        'contact.approach_retract[sphere-jkr](work_of_adhesion=huge) -> ValueError not naming '
        "work_of_adhesion: 'The function value at x=0.0 is NaN; solver cannot continue.'...'\n"
        'contact.approach_retract[sphere-jkr](work_of_adhesion=bigint) -> ValueError not namin'
        "g work_of_adhesion: 'z_np must be < -inf m for this sphere (R = 5e-08 m) with JKR adh"
        "esion (w = 1e+09 J/m^2, k ...'"
    ), False),
    'contact.approach_retract[sphere-jkr]:youngs_modulus': ((
        'contact.approach_retract[sphere-jkr](youngs_modulus=tiny) -> ValueError not naming yo'
        "ungs_modulus: 'z_np must be < -inf m for this sphere (R = 5e-08 m) with JKR adhesion "
        "(w = 0.03 J/m^2, k =...'"
    ), False),
    'contact.hereditary_force:time': ((
        "contact.hereditary_force(time=list) -> ValueError not naming time: 'indentation must "
        "have 2 elements (same as its companion array), got 50'"
    ), False),
    'contact.jkr_curve:contact_radius': ((
        'contact.jkr_curve(contact_radius=huge) -> returned non-finite (0: np.float64(inf))'
    ), False),
    'contact.jkr_curve:work_of_adhesion': ((
        'contact.jkr_curve(work_of_adhesion=huge) -> returned non-finite (1: array with 10 non'
        '-finite of 10)'
    ), False),
    'contact.jkr_instability:*': ((
        'contact.jkr_instability(radius=1e+202) -> OverflowError: "(34, \'Numerical result '
        'out of range\')"'
    ), False),
    'contact.jkr_instability:radius': ((
        'contact.jkr_instability(radius=huge) -> OverflowError: "(34, \'Numerical result ou'
        't of range\')"'
    ), False),
    'contact.jkr_instability:work_of_adhesion': ((
        'contact.jkr_instability(work_of_adhesion=huge) -> ValueError not naming work_of_adhes'
        "ion: 'The function value at x=0.0 is NaN; solver cannot continue.'...'"
    ), False),
    'contact.load_curve:*': ((
        "contact.load_curve(path=0.0) -> TypeError not naming path: 'expected str, bytes or os"
        ".PathLike object, not float'"
    ), False),
    'contact.load_curve:path': ((
        "contact.load_curve(path=nan) -> TypeError not naming path: 'expected str, bytes or os"
        ".PathLike object, not float'\n"
        "contact.load_curve(path=inf) -> TypeError not naming path: 'expected str, bytes or os"
        ".PathLike object, not float'\n"
        "contact.load_curve(path=-inf) -> TypeError not naming path: 'expected str, bytes or o"
        "s.PathLike object, not float'\n"
        'contact.load_curve(path=str) -> ValueError not naming path: "Unsupported file extensi'
        'on: \'1e-6\'!"\n'
        "contact.load_curve(path=bool) -> TypeError not naming path: 'expected str, bytes or o"
        "s.PathLike object, not bool'\n"
        "contact.load_curve(path=complex) -> TypeError not naming path: 'expected str, bytes o"
        "r os.PathLike object, not complex'\n"
        "contact.load_curve(path=list) -> TypeError not naming path: 'expected str, bytes or o"
        "s.PathLike object, not list'\n"
        "contact.load_curve(path=object) -> TypeError not naming path: 'expected str, bytes or"
        " os.PathLike object, not Foreign'\n"
        "contact.load_curve(path=zero) -> TypeError not naming path: 'expected str, bytes or o"
        "s.PathLike object, not float'\n"
        "contact.load_curve(path=negative) -> TypeError not naming path: 'expected str, bytes "
        "or os.PathLike object, not float'\n"
        "contact.load_curve(path=huge) -> TypeError not naming path: 'expected str, bytes or o"
        "s.PathLike object, not float'\n"
        "contact.load_curve(path=-huge) -> TypeError not naming path: 'expected str, bytes or "
        "os.PathLike object, not float'\n"
        "contact.load_curve(path=tiny) -> TypeError not naming path: 'expected str, bytes or o"
        "s.PathLike object, not float'\n"
        "contact.load_curve(path=bigint) -> TypeError not naming path: 'expected str, bytes or"
        " os.PathLike object, not int'\n"
        "contact.load_curve(path=2d) -> TypeError not naming path: 'expected str, bytes or os."
        "PathLike object, not ndarray'\n"
        "contact.load_curve(path=empty) -> TypeError not naming path: 'expected str, bytes or "
        "os.PathLike object, not ndarray'\n"
        "contact.load_curve(path=nan-array) -> TypeError not naming path: 'expected str, bytes"
        " or os.PathLike object, not ndarray'"
    ), False),
    'contact.load_curve:segment': ((
        "contact.load_curve(segment=2d) -> ValueError not naming segment: 'The truth value of "
        "an array with more than one element is ambiguous. Use a.any() or a.all(...'\n"
        "contact.load_curve(segment=empty) -> ValueError not naming segment: 'The truth value "
        "of an empty array is ambiguous. Use `array.size > 0` to check that an arra...'\n"
        "contact.load_curve(segment=nan-array) -> ValueError not naming segment: 'The truth va"
        "lue of an array with more than one element is ambiguous. Use a.any() or a.all(...'"
    ), False),
    'contact.make_tip:key': ((
        'contact.make_tip(key=list) -> TypeError not naming key: "unhashable type: \'list\'"\n'
        'contact.make_tip(key=2d) -> TypeError not naming key: "unhashable type: \'numpy.nd'
        'array\'"\n'
        'contact.make_tip(key=empty) -> TypeError not naming key: "unhashable type: \'numpy'
        '.ndarray\'"\n'
        'contact.make_tip(key=nan-array) -> TypeError not naming key: "unhashable type: \'n'
        'umpy.ndarray\'"'
    ), False),
    'contact.residual:*': ((
        'contact.residual(curve=0.0) -> AttributeError: "\'float\' object has no attribute \''
        'in_contact\'"'
    ), False),
    'contact.residual:curve': ((
        'contact.residual(curve=nan) -> AttributeError: "\'float\' object has no attribute \''
        'in_contact\'"\n'
        'contact.residual(curve=inf) -> AttributeError: "\'float\' object has no attribute \''
        'in_contact\'"\n'
        'contact.residual(curve=-inf) -> AttributeError: "\'float\' object has no attribute '
        '\'in_contact\'"\n'
        'contact.residual(curve=str) -> AttributeError: "\'str\' object has no attribute \'in'
        '_contact\'"\n'
        'contact.residual(curve=bool) -> AttributeError: "\'bool\' object has no attribute \''
        'in_contact\'"\n'
        'contact.residual(curve=complex) -> AttributeError: "\'complex\' object has no attri'
        'bute \'in_contact\'"\n'
        'contact.residual(curve=list) -> AttributeError: "\'list\' object has no attribute \''
        'in_contact\'"\n'
        'contact.residual(curve=object) -> AttributeError: "\'Foreign\' object has no attrib'
        'ute \'in_contact\'"\n'
        'contact.residual(curve=zero) -> AttributeError: "\'float\' object has no attribute '
        '\'in_contact\'"\n'
        'contact.residual(curve=negative) -> AttributeError: "\'float\' object has no attrib'
        'ute \'in_contact\'"\n'
        'contact.residual(curve=huge) -> AttributeError: "\'float\' object has no attribute '
        '\'in_contact\'"\n'
        'contact.residual(curve=-huge) -> AttributeError: "\'float\' object has no attribute'
        ' \'in_contact\'"\n'
        'contact.residual(curve=tiny) -> AttributeError: "\'float\' object has no attribute '
        '\'in_contact\'"\n'
        'contact.residual(curve=bigint) -> AttributeError: "\'int\' object has no attribute '
        '\'in_contact\'"\n'
        'contact.residual(curve=2d) -> AttributeError: "\'numpy.ndarray\' object has no attr'
        'ibute \'in_contact\'"\n'
        'contact.residual(curve=empty) -> AttributeError: "\'numpy.ndarray\' object has no a'
        'ttribute \'in_contact\'"\n'
        'contact.residual(curve=nan-array) -> AttributeError: "\'numpy.ndarray\' object has '
        'no attribute \'in_contact\'"'
    ), False),
    'contact.residual:tip': ((
        'contact.residual(tip=nan) -> AttributeError: "\'float\' object has no attribute \'fo'
        'rce\'"\n'
        'contact.residual(tip=inf) -> AttributeError: "\'float\' object has no attribute \'fo'
        'rce\'"\n'
        'contact.residual(tip=-inf) -> AttributeError: "\'float\' object has no attribute \'f'
        'orce\'"\n'
        'contact.residual(tip=str) -> AttributeError: "\'str\' object has no attribute \'forc'
        'e\'"\n'
        'contact.residual(tip=bool) -> AttributeError: "\'bool\' object has no attribute \'fo'
        'rce\'"\n'
        'contact.residual(tip=complex) -> AttributeError: "\'complex\' object has no attribu'
        'te \'force\'"\n'
        'contact.residual(tip=list) -> AttributeError: "\'list\' object has no attribute \'fo'
        'rce\'"\n'
        'contact.residual(tip=object) -> AttributeError: "\'Foreign\' object has no attribut'
        'e \'force\'"\n'
        'contact.residual(tip=zero) -> AttributeError: "\'float\' object has no attribute \'f'
        'orce\'"\n'
        'contact.residual(tip=negative) -> AttributeError: "\'float\' object has no attribut'
        'e \'force\'"\n'
        'contact.residual(tip=huge) -> AttributeError: "\'float\' object has no attribute \'f'
        'orce\'"\n'
        'contact.residual(tip=-huge) -> AttributeError: "\'float\' object has no attribute \''
        'force\'"\n'
        'contact.residual(tip=tiny) -> AttributeError: "\'float\' object has no attribute \'f'
        'orce\'"\n'
        'contact.residual(tip=bigint) -> AttributeError: "\'int\' object has no attribute \'f'
        'orce\'"\n'
        'contact.residual(tip=2d) -> AttributeError: "\'numpy.ndarray\' object has no attrib'
        'ute \'force\'"\n'
        'contact.residual(tip=empty) -> AttributeError: "\'numpy.ndarray\' object has no att'
        'ribute \'force\'"\n'
        'contact.residual(tip=nan-array) -> AttributeError: "\'numpy.ndarray\' object has no'
        ' attribute \'force\'"'
    ), False),
    'contact.surface_displacement:z_s': ((
        'contact.surface_displacement(z_s=list) -> TypeError not naming z_s: "float() argument'
        ' must be a string or a real number, not \'list\'"\n'
        "contact.surface_displacement(z_s=2d) -> TypeError not naming z_s: 'only 0-dimensional"
        " arrays can be converted to Python scalars'\n"
        "contact.surface_displacement(z_s=empty) -> TypeError not naming z_s: 'only 0-dimensio"
        "nal arrays can be converted to Python scalars'"
    ), False),
    'contact.synthetic_curve:*': ((
        'contact.synthetic_curve(z_np_range=0.0) -> TypeError not naming z_np_range: "\'flo'
        'at\' object is not subscriptable"'
    ), False),
    'contact.synthetic_curve:seed': ((
        "contact.synthetic_curve(seed=nan) -> TypeError not naming seed: 'SeedSequence expects"
        " int or sequence of ints for entropy not nan'\n"
        "contact.synthetic_curve(seed=inf) -> TypeError not naming seed: 'SeedSequence expects"
        " int or sequence of ints for entropy not inf'\n"
        "contact.synthetic_curve(seed=-inf) -> TypeError not naming seed: 'SeedSequence expect"
        "s int or sequence of ints for entropy not -inf'\n"
        "contact.synthetic_curve(seed=str) -> TypeError not naming seed: 'SeedSequence expects"
        " int or sequence of ints for entropy not 1e-6'\n"
        'contact.synthetic_curve(seed=bool) -> accepted silently\n'
        "contact.synthetic_curve(seed=complex) -> TypeError not naming seed: 'SeedSequence exp"
        "ects int or sequence of ints for entropy not (1+1j)'\n"
        "contact.synthetic_curve(seed=object) -> TypeError not naming seed: 'SeedSequence expe"
        "cts int or sequence of ints for entropy not Foreign()'\n"
        "contact.synthetic_curve(seed=zero) -> TypeError not naming seed: 'SeedSequence expect"
        "s int or sequence of ints for entropy not 0.0'\n"
        "contact.synthetic_curve(seed=negative) -> TypeError not naming seed: 'SeedSequence ex"
        "pects int or sequence of ints for entropy not -1.0'\n"
        "contact.synthetic_curve(seed=huge) -> TypeError not naming seed: 'SeedSequence expect"
        "s int or sequence of ints for entropy not 1e+300'\n"
        "contact.synthetic_curve(seed=-huge) -> TypeError not naming seed: 'SeedSequence expec"
        "ts int or sequence of ints for entropy not -1e+300'\n"
        "contact.synthetic_curve(seed=tiny) -> TypeError not naming seed: 'SeedSequence expect"
        "s int or sequence of ints for entropy not 1e-300'"
    ), False),
    'contact.synthetic_curve:z_np_range': ((
        'contact.synthetic_curve(z_np_range=nan) -> TypeError not naming z_np_range: "\'flo'
        'at\' object is not subscriptable"\n'
        'contact.synthetic_curve(z_np_range=inf) -> TypeError not naming z_np_range: "\'flo'
        'at\' object is not subscriptable"\n'
        'contact.synthetic_curve(z_np_range=-inf) -> TypeError not naming z_np_range: "\'fl'
        'oat\' object is not subscriptable"\n'
        'contact.synthetic_curve(z_np_range=None) -> TypeError not naming z_np_range: "\'No'
        'neType\' object is not subscriptable"\n'
        'contact.synthetic_curve(z_np_range=bool) -> TypeError not naming z_np_range: "\'bo'
        'ol\' object is not subscriptable"\n'
        'contact.synthetic_curve(z_np_range=complex) -> TypeError not naming z_np_range: "'
        '\'complex\' object is not subscriptable"\n'
        'contact.synthetic_curve(z_np_range=object) -> TypeError not naming z_np_range: "\''
        'Foreign\' object is not subscriptable"\n'
        'contact.synthetic_curve(z_np_range=zero) -> TypeError not naming z_np_range: "\'fl'
        'oat\' object is not subscriptable"\n'
        'contact.synthetic_curve(z_np_range=negative) -> TypeError not naming z_np_range: '
        '"\'float\' object is not subscriptable"\n'
        'contact.synthetic_curve(z_np_range=huge) -> TypeError not naming z_np_range: "\'fl'
        'oat\' object is not subscriptable"\n'
        'contact.synthetic_curve(z_np_range=-huge) -> TypeError not naming z_np_range: "\'f'
        'loat\' object is not subscriptable"\n'
        'contact.synthetic_curve(z_np_range=tiny) -> TypeError not naming z_np_range: "\'fl'
        'oat\' object is not subscriptable"\n'
        'contact.synthetic_curve(z_np_range=bigint) -> TypeError not naming z_np_range: "\''
        'int\' object is not subscriptable"\n'
        "contact.synthetic_curve(z_np_range=empty) -> IndexError: 'index 0 is out of bounds fo"
        "r axis 0 with size 0'"
    ), False),
    'contact.z_np_limit:work_of_adhesion': ((
        'contact.z_np_limit(work_of_adhesion=nan) -> accepted silently\n'
        'contact.z_np_limit(work_of_adhesion=None) -> accepted silently\n'
        'contact.z_np_limit(work_of_adhesion=str) -> accepted silently\n'
        'contact.z_np_limit(work_of_adhesion=bool) -> accepted silently\n'
        'contact.z_np_limit(work_of_adhesion=complex) -> accepted silently\n'
        'contact.z_np_limit(work_of_adhesion=object) -> accepted silently\n'
        'contact.z_np_limit(work_of_adhesion=nan-array) -> accepted silently'
    ), False),
    'contact.z_np_limit[sphere-jkr]:work_of_adhesion': ((
        'contact.z_np_limit[sphere-jkr](work_of_adhesion=huge) -> ValueError not naming work_o'
        "f_adhesion: 'The function value at x=0.0 is NaN; solver cannot continue.'...'"
    ), False),
    'controller.ContactLoop.closed_forms:input': ((
        "controller.ContactLoop.closed_forms(input=2d) -> ValueError not naming input: 'The tr"
        'uth value of an array with more than one element is ambiguous. Use a.any() or a.all(.'
        "..'\n"
        "controller.ContactLoop.closed_forms(input=empty) -> ValueError not naming input: 'The"
        ' truth value of an empty array is ambiguous. Use `array.size > 0` to check that an ar'
        "ra...'\n"
        'controller.ContactLoop.closed_forms(input=nan-array) -> ValueError not naming input: '
        "'The truth value of an array with more than one element is ambiguous. Use a.any() or "
        "a.all(...'"
    ), False),
    'controller.ContactLoop.scan_line:speed': ((
        'controller.ContactLoop.scan_line(speed=tiny) -> returned non-finite (trace: z_c: arra'
        'y with 16 non-finite of 16, 16 NaN)'
    ), False),
    'controller.ContactLoop.scan_line:x': ((
        "controller.ContactLoop.scan_line(x=list) -> ValueError not naming x: 'height must hav"
        "e 2 elements (same as its companion array), got 16'"
    ), False),
    'controller.ContactLoop:*': ((
        "controller.ContactLoop(b_s=1e+202) -> ZeroDivisionError: 'float division by zero'"
    ), False),
    'controller.ContactLoop:b_c': ((
        "controller.ContactLoop(b_c=huge) -> LinAlgError not naming b_c: 'Array must not conta"
        "in infs or NaNs'"
    ), False),
    'controller.ContactLoop:b_s': ((
        "controller.ContactLoop(b_s=huge) -> LinAlgError not naming b_s: 'Array must not conta"
        "in infs or NaNs'"
    ), False),
    'controller.ContactLoop:k_c': ((
        "controller.ContactLoop(k_c=huge) -> LinAlgError not naming k_c: 'Array must not conta"
        "in infs or NaNs'"
    ), False),
    'controller.ContactLoop:k_s': ((
        "controller.ContactLoop(k_s=huge) -> LinAlgError not naming k_s: 'Array must not conta"
        "in infs or NaNs'\n"
        "controller.ContactLoop(k_s=tiny) -> ZeroDivisionError: 'float division by zero'"
    ), False),
    'controller.ContactLoop:kd': ((
        "controller.ContactLoop(kd=huge) -> ZeroDivisionError: 'float division by zero'"
    ), False),
    'controller.ContactLoop:ki': ((
        "controller.ContactLoop(ki=huge) -> LinAlgError not naming ki: 'Array must not contain"
        " infs or NaNs'\n"
        "controller.ContactLoop(ki=tiny) -> ZeroDivisionError: 'float division by zero'"
    ), False),
    'controller.ContactLoop:kp': ((
        "controller.ContactLoop(kp=huge) -> LinAlgError not naming kp: 'Array must not contain"
        " infs or NaNs'"
    ), False),
    'controller.ContactLoop:m_c': ((
        'controller.ContactLoop(m_c=huge) -> OverflowError: "(34, \'Numerical result out of'
        ' range\')"'
    ), False),
    'controller.ContactLoop:m_s': ((
        'controller.ContactLoop(m_s=huge) -> OverflowError: "(34, \'Numerical result out of'
        ' range\')"'
    ), False),
    'controller.Preset.scan:*': ((
        'controller.Preset.scan(sample=0.0) -> AttributeError: "\'float\' object has no attr'
        'ibute \'x\'"'
    ), False),
    'controller.Preset.scan:sample': ((
        'controller.Preset.scan(sample=nan) -> AttributeError: "\'float\' object has no attr'
        'ibute \'x\'"\n'
        'controller.Preset.scan(sample=inf) -> AttributeError: "\'float\' object has no attr'
        'ibute \'x\'"\n'
        'controller.Preset.scan(sample=-inf) -> AttributeError: "\'float\' object has no att'
        'ribute \'x\'"\n'
        'controller.Preset.scan(sample=str) -> AttributeError: "\'str\' object has no attrib'
        'ute \'x\'"\n'
        'controller.Preset.scan(sample=bool) -> AttributeError: "\'bool\' object has no attr'
        'ibute \'x\'"\n'
        'controller.Preset.scan(sample=complex) -> AttributeError: "\'complex\' object has n'
        'o attribute \'x\'"\n'
        'controller.Preset.scan(sample=list) -> AttributeError: "\'list\' object has no attr'
        'ibute \'x\'"\n'
        'controller.Preset.scan(sample=object) -> AttributeError: "\'Foreign\' object has no'
        ' attribute \'x\'"\n'
        'controller.Preset.scan(sample=zero) -> AttributeError: "\'float\' object has no att'
        'ribute \'x\'"\n'
        'controller.Preset.scan(sample=negative) -> AttributeError: "\'float\' object has no'
        ' attribute \'x\'"\n'
        'controller.Preset.scan(sample=huge) -> AttributeError: "\'float\' object has no att'
        'ribute \'x\'"\n'
        'controller.Preset.scan(sample=-huge) -> AttributeError: "\'float\' object has no at'
        'tribute \'x\'"\n'
        'controller.Preset.scan(sample=tiny) -> AttributeError: "\'float\' object has no att'
        'ribute \'x\'"\n'
        'controller.Preset.scan(sample=bigint) -> AttributeError: "\'int\' object has no att'
        'ribute \'x\'"\n'
        'controller.Preset.scan(sample=2d) -> AttributeError: "\'numpy.ndarray\' object has '
        'no attribute \'x\'"\n'
        'controller.Preset.scan(sample=empty) -> AttributeError: "\'numpy.ndarray\' object h'
        'as no attribute \'x\'"\n'
        'controller.Preset.scan(sample=nan-array) -> AttributeError: "\'numpy.ndarray\' obje'
        'ct has no attribute \'x\'"'
    ), False),
    'controller.ScanImage.line:row': ((
        'controller.ScanImage.line(row=bool) -> accepted silently'
    ), False),
    'controller.classify_roots:roots': ((
        "controller.classify_roots(roots=object) -> TypeError not naming roots: 'must be real "
        "number, not Foreign'\n"
        'controller.classify_roots(roots=nan-array) -> accepted silently'
    ), False),
    'controller.classify_roots:tol': ((
        'controller.classify_roots(tol=nan) -> accepted silently\n'
        'controller.classify_roots(tol=None) -> TypeError not naming tol: "unsupported operand'
        ' type(s) for *: \'NoneType\' and \'float\'"\n'
        'controller.classify_roots(tol=str) -> TypeError not naming tol: "can\'t multiply s'
        'equence by non-int of type \'numpy.float64\'"\n'
        'controller.classify_roots(tol=bool) -> accepted silently\n'
        'controller.classify_roots(tol=complex) -> accepted silently\n'
        'controller.classify_roots(tol=list) -> TypeError not naming tol: "can\'t multiply '
        'sequence by non-int of type \'numpy.float64\'"\n'
        'controller.classify_roots(tol=object) -> TypeError not naming tol: "unsupported opera'
        'nd type(s) for *: \'Foreign\' and \'float\'"\n'
        "controller.classify_roots(tol=2d) -> ValueError not naming tol: 'The truth value of a"
        "n array with more than one element is ambiguous. Use a.any() or a.all(...'\n"
        "controller.classify_roots(tol=empty) -> ValueError not naming tol: 'The truth value o"
        "f an empty array is ambiguous. Use `array.size > 0` to check that an arra...'\n"
        "controller.classify_roots(tol=nan-array) -> ValueError not naming tol: 'The truth val"
        "ue of an array with more than one element is ambiguous. Use a.any() or a.all(...'"
    ), False),
    'controller.closed_form:*': ((
        'controller.closed_form(structure=0.0) -> KeyError: "\'step_o2_0.0\'"'
    ), False),
    'controller.closed_form:b': ((
        'controller.closed_form(b=str) -> TypeError not naming b: "step_o3_distinct() missing '
        '1 required positional argument: \'p3\'"\n'
        'controller.closed_form(b=list) -> KeyError: "\'step_o1_distinct\'"\n'
        'controller.closed_form(b=empty) -> KeyError: "\'step_o-1_distinct\'"\n'
        'controller.closed_form(b=nan-array) -> KeyError: "\'step_o1_distinct\'"'
    ), False),
    'controller.closed_form:input': ((
        'controller.closed_form(input=nan) -> KeyError: "\'nan_o2_distinct\'"\n'
        'controller.closed_form(input=inf) -> KeyError: "\'inf_o2_distinct\'"\n'
        'controller.closed_form(input=-inf) -> KeyError: "\'-inf_o2_distinct\'"\n'
        'controller.closed_form(input=None) -> KeyError: "\'None_o2_distinct\'"\n'
        'controller.closed_form(input=str) -> KeyError: "\'1e-6_o2_distinct\'"\n'
        'controller.closed_form(input=bool) -> KeyError: "\'True_o2_distinct\'"\n'
        'controller.closed_form(input=complex) -> KeyError: "\'(1+1j)_o2_distinct\'"\n'
        'controller.closed_form(input=list) -> KeyError: "\'[1.0, 2.0]_o2_distinct\'"\n'
        'controller.closed_form(input=object) -> KeyError: "\'Foreign()_o2_distinct\'"\n'
        'controller.closed_form(input=zero) -> KeyError: "\'0.0_o2_distinct\'"\n'
        'controller.closed_form(input=negative) -> KeyError: "\'-1.0_o2_distinct\'"\n'
        'controller.closed_form(input=huge) -> KeyError: "\'1e+300_o2_distinct\'"\n'
        'controller.closed_form(input=-huge) -> KeyError: "\'-1e+300_o2_distinct\'"\n'
        'controller.closed_form(input=tiny) -> KeyError: "\'1e-300_o2_distinct\'"\n'
        'controller.closed_form(input=bigint) -> KeyError: "\'1000000000_o2_distinct\'"\n'
        'controller.closed_form(input=2d) -> KeyError: "\'[[1. 1. 1.]\\\\n [1. 1. 1.]\\\\n '
        '[1. 1. 1.]]_o2_distinct\'"\n'
        'controller.closed_form(input=empty) -> KeyError: "\'[]_o2_distinct\'"\n'
        'controller.closed_form(input=nan-array) -> KeyError: "\'[ 0. nan]_o2_distinct\'"'
    ), False),
    'controller.closed_form:params': ((
        "controller.closed_form(params=nan) -> TypeError not naming params: 'Value after * mus"
        "t be an iterable, not float'\n"
        "controller.closed_form(params=inf) -> TypeError not naming params: 'Value after * mus"
        "t be an iterable, not float'\n"
        "controller.closed_form(params=-inf) -> TypeError not naming params: 'Value after * mu"
        "st be an iterable, not float'\n"
        "controller.closed_form(params=str) -> TypeError not naming params: 'step_o2_distinct("
        ") takes 3 positional arguments but 5 were given'\n"
        "controller.closed_form(params=bool) -> TypeError not naming params: 'Value after * mu"
        "st be an iterable, not bool'\n"
        "controller.closed_form(params=complex) -> TypeError not naming params: 'Value after *"
        " must be an iterable, not complex'\n"
        "controller.closed_form(params=object) -> TypeError not naming params: 'Value after * "
        "must be an iterable, not Foreign'\n"
        "controller.closed_form(params=zero) -> TypeError not naming params: 'Value after * mu"
        "st be an iterable, not float'\n"
        "controller.closed_form(params=negative) -> TypeError not naming params: 'Value after "
        "* must be an iterable, not float'\n"
        "controller.closed_form(params=huge) -> TypeError not naming params: 'Value after * mu"
        "st be an iterable, not float'\n"
        "controller.closed_form(params=-huge) -> TypeError not naming params: 'Value after * m"
        "ust be an iterable, not float'\n"
        "controller.closed_form(params=tiny) -> TypeError not naming params: 'Value after * mu"
        "st be an iterable, not float'\n"
        "controller.closed_form(params=bigint) -> TypeError not naming params: 'Value after * "
        "must be an iterable, not int'\n"
        "controller.closed_form(params=2d) -> TypeError not naming params: 'step_o2_distinct()"
        " takes 3 positional arguments but 4 were given'\n"
        'controller.closed_form(params=empty) -> TypeError not naming params: "step_o2_distinc'
        't() missing 2 required positional arguments: \'p1\' and \'p2\'"\n'
        'controller.closed_form(params=nan-array) -> accepted silently'
    ), False),
    'controller.closed_form:structure': ((
        'controller.closed_form(structure=nan) -> KeyError: "\'step_o2_nan\'"\n'
        'controller.closed_form(structure=inf) -> KeyError: "\'step_o2_inf\'"\n'
        'controller.closed_form(structure=-inf) -> KeyError: "\'step_o2_-inf\'"\n'
        'controller.closed_form(structure=str) -> KeyError: "\'step_o2_1e-6\'"\n'
        'controller.closed_form(structure=bool) -> KeyError: "\'step_o2_True\'"\n'
        'controller.closed_form(structure=complex) -> KeyError: "\'step_o2_(1+1j)\'"\n'
        'controller.closed_form(structure=list) -> KeyError: "\'step_o2_[1.0, 2.0]\'"\n'
        'controller.closed_form(structure=object) -> KeyError: "\'step_o2_Foreign()\'"\n'
        'controller.closed_form(structure=zero) -> KeyError: "\'step_o2_0.0\'"\n'
        'controller.closed_form(structure=negative) -> KeyError: "\'step_o2_-1.0\'"\n'
        'controller.closed_form(structure=huge) -> KeyError: "\'step_o2_1e+300\'"\n'
        'controller.closed_form(structure=-huge) -> KeyError: "\'step_o2_-1e+300\'"\n'
        'controller.closed_form(structure=tiny) -> KeyError: "\'step_o2_1e-300\'"\n'
        'controller.closed_form(structure=bigint) -> KeyError: "\'step_o2_1000000000\'"\n'
        "controller.closed_form(structure=2d) -> ValueError not naming structure: 'The truth v"
        "alue of an array with more than one element is ambiguous. Use a.any() or a.all(...'\n"
        "controller.closed_form(structure=empty) -> ValueError not naming structure: 'The trut"
        'h value of an empty array is ambiguous. Use `array.size > 0` to check that an arra...'
        "'\n"
        "controller.closed_form(structure=nan-array) -> ValueError not naming structure: 'The "
        'truth value of an array with more than one element is ambiguous. Use a.any() or a.all'
        "(...'"
    ), False),
    'controller.routh_hurwitz:*': ((
        'controller.routh_hurwitz(den=0.0) -> TypeError not naming den: "\'float\' object is'
        ' not iterable"'
    ), False),
    'controller.routh_hurwitz:den': ((
        'controller.routh_hurwitz(den=nan) -> TypeError not naming den: "\'float\' object is'
        ' not iterable"\n'
        'controller.routh_hurwitz(den=inf) -> TypeError not naming den: "\'float\' object is'
        ' not iterable"\n'
        'controller.routh_hurwitz(den=-inf) -> TypeError not naming den: "\'float\' object i'
        's not iterable"\n'
        'controller.routh_hurwitz(den=str) -> ValueError not naming den: "could not convert st'
        'ring to float: \'e\'"\n'
        'controller.routh_hurwitz(den=bool) -> TypeError not naming den: "\'bool\' object is'
        ' not iterable"\n'
        'controller.routh_hurwitz(den=complex) -> TypeError not naming den: "\'complex\' obj'
        'ect is not iterable"\n'
        'controller.routh_hurwitz(den=object) -> TypeError not naming den: "\'Foreign\' obje'
        'ct is not iterable"\n'
        'controller.routh_hurwitz(den=zero) -> TypeError not naming den: "\'float\' object i'
        's not iterable"\n'
        'controller.routh_hurwitz(den=negative) -> TypeError not naming den: "\'float\' obje'
        'ct is not iterable"\n'
        'controller.routh_hurwitz(den=huge) -> TypeError not naming den: "\'float\' object i'
        's not iterable"\n'
        'controller.routh_hurwitz(den=-huge) -> TypeError not naming den: "\'float\' object '
        'is not iterable"\n'
        'controller.routh_hurwitz(den=tiny) -> TypeError not naming den: "\'float\' object i'
        's not iterable"\n'
        'controller.routh_hurwitz(den=bigint) -> TypeError not naming den: "\'int\' object i'
        's not iterable"\n'
        "controller.routh_hurwitz(den=2d) -> TypeError not naming den: 'only 0-dimensional arr"
        "ays can be converted to Python scalars'"
    ), False),
    'controller.scan_image:*': ((
        'controller.scan_image(loop=0.0) -> AttributeError: "\'float\' object has no attribu'
        'te \'_forms\'"'
    ), False),
    'controller.scan_image:loop': ((
        'controller.scan_image(loop=nan) -> AttributeError: "\'float\' object has no attribu'
        'te \'_forms\'"\n'
        'controller.scan_image(loop=inf) -> AttributeError: "\'float\' object has no attribu'
        'te \'_forms\'"\n'
        'controller.scan_image(loop=-inf) -> AttributeError: "\'float\' object has no attrib'
        'ute \'_forms\'"\n'
        'controller.scan_image(loop=str) -> AttributeError: "\'str\' object has no attribute'
        ' \'_forms\'"\n'
        'controller.scan_image(loop=bool) -> AttributeError: "\'bool\' object has no attribu'
        'te \'_forms\'"\n'
        'controller.scan_image(loop=complex) -> AttributeError: "\'complex\' object has no a'
        'ttribute \'_forms\'"\n'
        'controller.scan_image(loop=list) -> AttributeError: "\'list\' object has no attribu'
        'te \'_forms\'"\n'
        'controller.scan_image(loop=object) -> AttributeError: "\'Foreign\' object has no at'
        'tribute \'_forms\'"\n'
        'controller.scan_image(loop=zero) -> AttributeError: "\'float\' object has no attrib'
        'ute \'_forms\'"\n'
        'controller.scan_image(loop=negative) -> AttributeError: "\'float\' object has no at'
        'tribute \'_forms\'"\n'
        'controller.scan_image(loop=huge) -> AttributeError: "\'float\' object has no attrib'
        'ute \'_forms\'"\n'
        'controller.scan_image(loop=-huge) -> AttributeError: "\'float\' object has no attri'
        'bute \'_forms\'"\n'
        'controller.scan_image(loop=tiny) -> AttributeError: "\'float\' object has no attrib'
        'ute \'_forms\'"\n'
        'controller.scan_image(loop=bigint) -> AttributeError: "\'int\' object has no attrib'
        'ute \'_forms\'"\n'
        'controller.scan_image(loop=2d) -> AttributeError: "\'numpy.ndarray\' object has no '
        'attribute \'_forms\'"\n'
        'controller.scan_image(loop=empty) -> AttributeError: "\'numpy.ndarray\' object has '
        'no attribute \'_forms\'"\n'
        'controller.scan_image(loop=nan-array) -> AttributeError: "\'numpy.ndarray\' object '
        'has no attribute \'_forms\'"'
    ), False),
    'controller.scan_image:pixel_size': ((
        'controller.scan_image(pixel_size=huge) -> returned non-finite (trace: array with 64 n'
        'on-finite of 64, 64 NaN)'
    ), False),
    'controller.scan_image:speed': ((
        'controller.scan_image(speed=tiny) -> returned non-finite (trace: array with 64 non-fi'
        'nite of 64, 64 NaN)'
    ), False),
    'materials.Material:name': ((
        'materials.Material(name=nan) -> accepted silently\n'
        'materials.Material(name=bool) -> accepted silently\n'
        'materials.Material(name=complex) -> accepted silently\n'
        'materials.Material(name=object) -> accepted silently\n'
        'materials.Material(name=nan-array) -> accepted silently'
    ), False),
    'materials.Material:source': ((
        'materials.Material(source=nan) -> accepted silently\n'
        'materials.Material(source=bool) -> accepted silently\n'
        'materials.Material(source=complex) -> accepted silently\n'
        'materials.Material(source=object) -> accepted silently\n'
        'materials.Material(source=nan-array) -> accepted silently'
    ), False),
    'materials.get_material:*': ((
        'materials.get_material(name=0.0) -> ValueError not naming name: "material must be one'
        " of ['aluminium', 'gold', 'quartz', 'silicon', 'silicon_dioxide', 'sil...'"
    ), False),
    'materials.get_material:name': ((
        'materials.get_material(name=nan) -> ValueError not naming name: "material must be one'
        " of ['aluminium', 'gold', 'quartz', 'silicon', 'silicon_dioxide', 'sil...'\n"
        'materials.get_material(name=inf) -> ValueError not naming name: "material must be one'
        " of ['aluminium', 'gold', 'quartz', 'silicon', 'silicon_dioxide', 'sil...'\n"
        'materials.get_material(name=-inf) -> ValueError not naming name: "material must be on'
        "e of ['aluminium', 'gold', 'quartz', 'silicon', 'silicon_dioxide', 'sil...'\n"
        'materials.get_material(name=str) -> ValueError not naming name: "material must be one'
        " of ['aluminium', 'gold', 'quartz', 'silicon', 'silicon_dioxide', 'sil...'\n"
        'materials.get_material(name=bool) -> ValueError not naming name: "material must be on'
        "e of ['aluminium', 'gold', 'quartz', 'silicon', 'silicon_dioxide', 'sil...'\n"
        'materials.get_material(name=complex) -> ValueError not naming name: "material must be'
        " one of ['aluminium', 'gold', 'quartz', 'silicon', 'silicon_dioxide', 'sil...'\n"
        'materials.get_material(name=list) -> TypeError not naming name: "unhashable type:'
        ' \'list\'"\n'
        'materials.get_material(name=object) -> ValueError not naming name: "material must be '
        "one of ['aluminium', 'gold', 'quartz', 'silicon', 'silicon_dioxide', 'sil...'\n"
        'materials.get_material(name=zero) -> ValueError not naming name: "material must be on'
        "e of ['aluminium', 'gold', 'quartz', 'silicon', 'silicon_dioxide', 'sil...'\n"
        'materials.get_material(name=negative) -> ValueError not naming name: "material must b'
        "e one of ['aluminium', 'gold', 'quartz', 'silicon', 'silicon_dioxide', 'sil...'\n"
        'materials.get_material(name=huge) -> ValueError not naming name: "material must be on'
        "e of ['aluminium', 'gold', 'quartz', 'silicon', 'silicon_dioxide', 'sil...'\n"
        'materials.get_material(name=-huge) -> ValueError not naming name: "material must be o'
        "ne of ['aluminium', 'gold', 'quartz', 'silicon', 'silicon_dioxide', 'sil...'\n"
        'materials.get_material(name=tiny) -> ValueError not naming name: "material must be on'
        "e of ['aluminium', 'gold', 'quartz', 'silicon', 'silicon_dioxide', 'sil...'\n"
        'materials.get_material(name=bigint) -> ValueError not naming name: "material must be '
        "one of ['aluminium', 'gold', 'quartz', 'silicon', 'silicon_dioxide', 'sil...'\n"
        'materials.get_material(name=2d) -> TypeError not naming name: "unhashable type: \''
        'numpy.ndarray\'"\n'
        'materials.get_material(name=empty) -> TypeError not naming name: "unhashable type'
        ': \'numpy.ndarray\'"\n'
        'materials.get_material(name=nan-array) -> TypeError not naming name: "unhashable type'
        ': \'numpy.ndarray\'"'
    ), False),
    'samples.Sample:name': ((
        'samples.Sample(name=nan) -> accepted silently\n'
        'samples.Sample(name=bool) -> accepted silently\n'
        'samples.Sample(name=complex) -> accepted silently\n'
        'samples.Sample(name=object) -> accepted silently\n'
        'samples.Sample(name=nan-array) -> accepted silently'
    ), False),
    'samples.from_file:*': ((
        "samples.from_file(path=0.0) -> TypeError not naming path: 'expected str, bytes or os."
        "PathLike object, not float'"
    ), False),
    'samples.from_file:path': ((
        "samples.from_file(path=nan) -> TypeError not naming path: 'expected str, bytes or os."
        "PathLike object, not float'\n"
        "samples.from_file(path=inf) -> TypeError not naming path: 'expected str, bytes or os."
        "PathLike object, not float'\n"
        "samples.from_file(path=-inf) -> TypeError not naming path: 'expected str, bytes or os"
        ".PathLike object, not float'\n"
        "samples.from_file(path=bool) -> TypeError not naming path: 'expected str, bytes or os"
        ".PathLike object, not bool'\n"
        "samples.from_file(path=complex) -> TypeError not naming path: 'expected str, bytes or"
        " os.PathLike object, not complex'\n"
        "samples.from_file(path=list) -> TypeError not naming path: 'expected str, bytes or os"
        ".PathLike object, not list'\n"
        "samples.from_file(path=object) -> TypeError not naming path: 'expected str, bytes or "
        "os.PathLike object, not Foreign'\n"
        "samples.from_file(path=zero) -> TypeError not naming path: 'expected str, bytes or os"
        ".PathLike object, not float'\n"
        "samples.from_file(path=negative) -> TypeError not naming path: 'expected str, bytes o"
        "r os.PathLike object, not float'\n"
        "samples.from_file(path=huge) -> TypeError not naming path: 'expected str, bytes or os"
        ".PathLike object, not float'\n"
        "samples.from_file(path=-huge) -> TypeError not naming path: 'expected str, bytes or o"
        "s.PathLike object, not float'\n"
        "samples.from_file(path=tiny) -> TypeError not naming path: 'expected str, bytes or os"
        ".PathLike object, not float'\n"
        "samples.from_file(path=bigint) -> TypeError not naming path: 'expected str, bytes or "
        "os.PathLike object, not int'\n"
        "samples.from_file(path=2d) -> TypeError not naming path: 'expected str, bytes or os.P"
        "athLike object, not ndarray'\n"
        "samples.from_file(path=empty) -> TypeError not naming path: 'expected str, bytes or o"
        "s.PathLike object, not ndarray'\n"
        "samples.from_file(path=nan-array) -> TypeError not naming path: 'expected str, bytes "
        "or os.PathLike object, not ndarray'"
    ), False),
    'samples.particles:*': ((
        'samples.particles(shape=0.0) -> TypeError not naming shape: "\'float\' object is no'
        't iterable"'
    ), False),
    'samples.particles:pixel_size': ((
        'samples.particles(pixel_size=None) -> TypeError not naming pixel_size: "unsupported o'
        'perand type(s) for *: \'int\' and \'NoneType\'"\n'
        'samples.particles(pixel_size=object) -> TypeError not naming pixel_size: "unsupported'
        ' operand type(s) for *: \'int\' and \'Foreign\'"\n'
        'samples.particles(pixel_size=huge) -> OverflowError: "(34, \'Numerical result out '
        'of range\')"\n'
        "samples.particles(pixel_size=tiny) -> ValueError not naming pixel_size: 'heights must"
        " be finite (in m), got nan (at index 0)'"
    ), False),
    'samples.particles:radius': ((
        'samples.particles(radius=huge) -> OverflowError: "(34, \'Numerical result out of r'
        'ange\')"'
    ), False),
    'samples.particles:shape': ((
        'samples.particles(shape=nan) -> TypeError not naming shape: "\'float\' object is no'
        't iterable"\n'
        'samples.particles(shape=inf) -> TypeError not naming shape: "\'float\' object is no'
        't iterable"\n'
        'samples.particles(shape=-inf) -> TypeError not naming shape: "\'float\' object is n'
        'ot iterable"\n'
        'samples.particles(shape=None) -> TypeError not naming shape: "\'NoneType\' object i'
        's not iterable"\n'
        'samples.particles(shape=bool) -> TypeError not naming shape: "\'bool\' object is no'
        't iterable"\n'
        'samples.particles(shape=complex) -> TypeError not naming shape: "\'complex\' object'
        ' is not iterable"\n'
        'samples.particles(shape=object) -> TypeError not naming shape: "\'Foreign\' object '
        'is not iterable"\n'
        'samples.particles(shape=zero) -> TypeError not naming shape: "\'float\' object is n'
        'ot iterable"\n'
        'samples.particles(shape=negative) -> TypeError not naming shape: "\'float\' object '
        'is not iterable"\n'
        'samples.particles(shape=huge) -> TypeError not naming shape: "\'float\' object is n'
        'ot iterable"\n'
        'samples.particles(shape=-huge) -> TypeError not naming shape: "\'float\' object is '
        'not iterable"\n'
        'samples.particles(shape=tiny) -> TypeError not naming shape: "\'float\' object is n'
        'ot iterable"\n'
        'samples.particles(shape=bigint) -> TypeError not naming shape: "\'int\' object is n'
        'ot iterable"\n'
        "samples.particles(shape=empty) -> ValueError not naming shape: 'not enough values to "
        "unpack (expected 2, got 0)'"
    ), False),
    'samples.rough_surface:*': ((
        'samples.rough_surface(shape=0.0) -> TypeError not naming shape: "\'float\' object i'
        's not iterable"'
    ), False),
    'samples.rough_surface:correlation_length': ((
        'samples.rough_surface(correlation_length=huge) -> OverflowError: "(34, \'Numerical'
        ' result out of range\')"'
    ), False),
    'samples.rough_surface:shape': ((
        'samples.rough_surface(shape=nan) -> TypeError not naming shape: "\'float\' object i'
        's not iterable"\n'
        'samples.rough_surface(shape=inf) -> TypeError not naming shape: "\'float\' object i'
        's not iterable"\n'
        'samples.rough_surface(shape=-inf) -> TypeError not naming shape: "\'float\' object '
        'is not iterable"\n'
        'samples.rough_surface(shape=None) -> TypeError not naming shape: "\'NoneType\' obje'
        'ct is not iterable"\n'
        'samples.rough_surface(shape=complex) -> TypeError not naming shape: "\'complex\' ob'
        'ject is not iterable"\n'
        'samples.rough_surface(shape=object) -> TypeError not naming shape: "\'Foreign\' obj'
        'ect is not iterable"\n'
        'samples.rough_surface(shape=zero) -> TypeError not naming shape: "\'float\' object '
        'is not iterable"\n'
        'samples.rough_surface(shape=negative) -> TypeError not naming shape: "\'float\' obj'
        'ect is not iterable"\n'
        'samples.rough_surface(shape=huge) -> TypeError not naming shape: "\'float\' object '
        'is not iterable"\n'
        'samples.rough_surface(shape=-huge) -> TypeError not naming shape: "\'float\' object'
        ' is not iterable"\n'
        'samples.rough_surface(shape=tiny) -> TypeError not naming shape: "\'float\' object '
        'is not iterable"'
    ), False),
    'transducers.AstigmaticDetection.focus_error:d': ((
        'transducers.AstigmaticDetection.focus_error(d=huge) -> returned non-finite (np.float6'
        '4(nan))\n'
        'transducers.AstigmaticDetection.focus_error(d=-huge) -> returned non-finite (np.float'
        '64(nan))'
    ), False),
    'transducers.AstigmaticDetection.spot_radii:d': ((
        'transducers.AstigmaticDetection.spot_radii(d=huge) -> returned non-finite (0: np.floa'
        't64(inf))\n'
        'transducers.AstigmaticDetection.spot_radii(d=-huge) -> returned non-finite (0: np.flo'
        'at64(inf))'
    ), False),
    'transducers.Photothermal.frequency_response:f': ((
        'transducers.Photothermal.frequency_response(f=huge) -> returned non-finite (response:'
        ' np.complex128(nan+nanj))'
    ), False),
    'transducers.Photothermal.thermal_lag:f': ((
        'transducers.Photothermal.thermal_lag(f=huge) -> returned non-finite (array with 1 non'
        '-finite of 1, 1 NaN)'
    ), False),
    'transducers.PiezoAcoustic.base_transfer:f': ((
        'transducers.PiezoAcoustic.base_transfer(f=huge) -> returned non-finite (np.complex128'
        '(nan+nanj))'
    ), False),
    'transducers.PiezoAcoustic.frequency_response:f': ((
        'transducers.PiezoAcoustic.frequency_response(f=huge) -> returned non-finite (response'
        ': np.complex128(nan+nanj))'
    ), False),
    'transducers.SignalChain.stage:name': ((
        "transducers.SignalChain.stage(name=2d) -> ValueError not naming name: 'The truth valu"
        "e of an array with more than one element is ambiguous. Use a.any() or a.all(...'\n"
        "transducers.SignalChain.stage(name=empty) -> ValueError not naming name: 'The truth v"
        "alue of an empty array is ambiguous. Use `array.size > 0` to check that an arra...'\n"
        "transducers.SignalChain.stage(name=nan-array) -> ValueError not naming name: 'The tru"
        'th value of an array with more than one element is ambiguous. Use a.any() or a.all(..'
        ".'"
    ), False),
}

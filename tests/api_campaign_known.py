"""Known failures of the bad-input campaign (tests/test_api_campaign.py), as strict xfails.

``"module.callable:parameter"`` -> (what fails, slow): each call listed fails today (written by
``python tests/api_campaign_record.py`` from a run of the campaign, then read). Fix them and delete
the entry (strict: a fixed entry turns the run red until it is deleted). ``slow`` marks an entry
whose calls hang until the campaign's 10 s alarm. ``"module.callable:*"`` is the hypothesis search
over random numbers for that callable (its first failing example).
"""

KNOWN = {
    'exercises.controller.height_error:profile': ((
        'exercises.controller.height_error(profile=nan) -> ValueError not naming profile: "nam'
        'e must be one of [\'grating\', \'particles\', \'real line\', \'step\'], got nan".'
        "..'\n"
        'exercises.controller.height_error(profile=inf) -> ValueError not naming profile: "nam'
        'e must be one of [\'grating\', \'particles\', \'real line\', \'step\'], got inf".'
        "..'\n"
        'exercises.controller.height_error(profile=-inf) -> ValueError not naming profile: "na'
        'me must be one of [\'grating\', \'particles\', \'real line\', \'step\'], got -inf"...'
        "'\n"
        'exercises.controller.height_error(profile=None) -> ValueError not naming profile: "na'
        'me must be one of [\'grating\', \'particles\', \'real line\', \'step\'], got None"...'
        "'\n"
        'exercises.controller.height_error(profile=str) -> ValueError not naming profile: "nam'
        "e must be one of ['grating', 'particles', 'real line', 'step'], got '1e-6"
        '\'"...\'\n'
        'exercises.controller.height_error(profile=bool) -> ValueError not naming profile: "na'
        'me must be one of [\'grating\', \'particles\', \'real line\', \'step\'], got True"...'
        "'\n"
        'exercises.controller.height_error(profile=complex) -> ValueError not naming profile: '
        '"name must be one of [\'grating\', \'particles\', \'real line\', \'step\'], got (1+1j'
        ')"...\'\n'
        'exercises.controller.height_error(profile=list) -> ValueError not naming profile: "na'
        "me must be one of ['grating', 'particles', 'real line', 'step'], got [1.0, 2."
        '0]"...\'\n'
        'exercises.controller.height_error(profile=object) -> ValueError not naming profile: "'
        "name must be one of ['grating', 'particles', 'real line', 'step'], got Foreig"
        'n()"...\'\n'
        'exercises.controller.height_error(profile=zero) -> ValueError not naming profile: "na'
        'me must be one of [\'grating\', \'particles\', \'real line\', \'step\'], got 0.0"'
        "...'\n"
        'exercises.controller.height_error(profile=negative) -> ValueError not naming profile:'
        ' "name must be one of [\'grating\', \'particles\', \'real line\', \'step\'], got -1.0'
        '"...\'\n'
        'exercises.controller.height_error(profile=huge) -> ValueError not naming profile: "na'
        'me must be one of [\'grating\', \'particles\', \'real line\', \'step\'], got 1e+300".'
        "..'\n"
        'exercises.controller.height_error(profile=-huge) -> ValueError not naming profile: "n'
        "ame must be one of ['grating', 'particles', 'real line', 'step'], got -1e+300"
        '"...\'\n'
        'exercises.controller.height_error(profile=tiny) -> ValueError not naming profile: "na'
        'me must be one of [\'grating\', \'particles\', \'real line\', \'step\'], got 1e-300".'
        "..'\n"
        'exercises.controller.height_error(profile=bigint) -> ValueError not naming profile: "'
        "name must be one of ['grating', 'particles', 'real line', 'step'], got 1000000000"
        '"...\'\n'
        'exercises.controller.height_error(profile=hugeint) -> ValueError not naming profile: '
        '"name must be one of [\'grating\', \'particles\', \'real line\', \'step\'], got 10000'
        "00000000000000...'\n"
        'exercises.controller.height_error(profile=2d) -> ValueError not naming profile: "name'
        " must be one of ['grating', 'particles', 'real line', 'step'], got array([[1., 1., 1."
        "]...'\n"
        'exercises.controller.height_error(profile=empty) -> ValueError not naming profile: "n'
        "ame must be one of ['grating', 'particles', 'real line', 'step'], got array([], dtype"
        "=flo...'\n"
        'exercises.controller.height_error(profile=nan-array) -> ValueError not naming profile'
        ': "name must be one of [\'grating\', \'particles\', \'real line\', \'step\'], got arr'
        'ay([ 0., nan])"...\''
    ), False),
    'exercises.imaging.check_apparent_width:rtol': ((
        'exercises.imaging.check_apparent_width(rtol=None) -> TypeError not naming rtol: "'
        '\'<=\' not supported between instances of \'float\' and \'NoneType\'"\n'
        'exercises.imaging.check_apparent_width(rtol=str) -> TypeError not naming rtol: "\''
        '<=\' not supported between instances of \'float\' and \'str\'"\n'
        'exercises.imaging.check_apparent_width(rtol=complex) -> TypeError not naming rtol'
        ': "\'<=\' not supported between instances of \'float\' and \'complex\'"\n'
        'exercises.imaging.check_apparent_width(rtol=list) -> TypeError not naming rtol: "'
        '\'<=\' not supported between instances of \'float\' and \'list\'"\n'
        'exercises.imaging.check_apparent_width(rtol=object) -> TypeError not naming rtol:'
        ' "\'<=\' not supported between instances of \'float\' and \'Foreign\'"\n'
        "exercises.imaging.check_apparent_width(rtol=2d) -> ValueError not naming rtol: 'The t"
        'ruth value of an array with more than one element is ambiguous. Use a.any() or a.all('
        "...'\n"
        "exercises.imaging.check_apparent_width(rtol=empty) -> ValueError not naming rtol: 'Th"
        'e truth value of an empty array is ambiguous. Use `array.size > 0` to check that an a'
        "rra...'\n"
        'exercises.imaging.check_apparent_width(rtol=nan-array) -> ValueError not naming rtol:'
        " 'The truth value of an array with more than one element is ambiguous. Use a.any() or"
        " a.all(...'"
    ), False),
    'exercises.imaging.check_tip_radius:rtol': ((
        'exercises.imaging.check_tip_radius(rtol=None) -> TypeError not naming rtol: "\'<=\''
        ' not supported between instances of \'float\' and \'NoneType\'"\n'
        'exercises.imaging.check_tip_radius(rtol=str) -> TypeError not naming rtol: "\'<=\' '
        'not supported between instances of \'float\' and \'str\'"\n'
        'exercises.imaging.check_tip_radius(rtol=complex) -> TypeError not naming rtol: "\''
        '<=\' not supported between instances of \'float\' and \'complex\'"\n'
        'exercises.imaging.check_tip_radius(rtol=list) -> TypeError not naming rtol: "\'<=\''
        ' not supported between instances of \'float\' and \'list\'"\n'
        'exercises.imaging.check_tip_radius(rtol=object) -> TypeError not naming rtol: "\'<'
        '=\' not supported between instances of \'float\' and \'Foreign\'"\n'
        "exercises.imaging.check_tip_radius(rtol=2d) -> ValueError not naming rtol: 'The truth"
        " value of an array with more than one element is ambiguous. Use a.any() or a.all(...'"
        '\n'
        "exercises.imaging.check_tip_radius(rtol=empty) -> ValueError not naming rtol: 'The tr"
        'uth value of an empty array is ambiguous. Use `array.size > 0` to check that an arra.'
        "..'\n"
        "exercises.imaging.check_tip_radius(rtol=nan-array) -> ValueError not naming rtol: 'Th"
        'e truth value of an array with more than one element is ambiguous. Use a.any() or a.a'
        "ll(...'"
    ), False),
    'plots.cantilever.ModeShapesFigure:ax': ((
        'plots.cantilever.ModeShapesFigure(ax=nan) -> AttributeError: "\'float\' object has '
        'no attribute \'figure\'"\n'
        'plots.cantilever.ModeShapesFigure(ax=inf) -> AttributeError: "\'float\' object has '
        'no attribute \'figure\'"\n'
        'plots.cantilever.ModeShapesFigure(ax=-inf) -> AttributeError: "\'float\' object has'
        ' no attribute \'figure\'"\n'
        'plots.cantilever.ModeShapesFigure(ax=str) -> AttributeError: "\'str\' object has no'
        ' attribute \'figure\'"\n'
        'plots.cantilever.ModeShapesFigure(ax=bool) -> AttributeError: "\'bool\' object has '
        'no attribute \'figure\'"\n'
        'plots.cantilever.ModeShapesFigure(ax=complex) -> AttributeError: "\'complex\' objec'
        't has no attribute \'figure\'"\n'
        'plots.cantilever.ModeShapesFigure(ax=list) -> AttributeError: "\'list\' object has '
        'no attribute \'figure\'"\n'
        'plots.cantilever.ModeShapesFigure(ax=object) -> AttributeError: "\'Foreign\' object'
        ' has no attribute \'figure\'"\n'
        'plots.cantilever.ModeShapesFigure(ax=zero) -> AttributeError: "\'float\' object has'
        ' no attribute \'figure\'"\n'
        'plots.cantilever.ModeShapesFigure(ax=negative) -> AttributeError: "\'float\' object'
        ' has no attribute \'figure\'"\n'
        'plots.cantilever.ModeShapesFigure(ax=huge) -> AttributeError: "\'float\' object has'
        ' no attribute \'figure\'"\n'
        'plots.cantilever.ModeShapesFigure(ax=-huge) -> AttributeError: "\'float\' object ha'
        's no attribute \'figure\'"\n'
        'plots.cantilever.ModeShapesFigure(ax=tiny) -> AttributeError: "\'float\' object has'
        ' no attribute \'figure\'"\n'
        'plots.cantilever.ModeShapesFigure(ax=bigint) -> AttributeError: "\'int\' object has'
        ' no attribute \'figure\'"\n'
        'plots.cantilever.ModeShapesFigure(ax=hugeint) -> AttributeError: "\'int\' object ha'
        's no attribute \'figure\'"\n'
        'plots.cantilever.ModeShapesFigure(ax=2d) -> AttributeError: "\'numpy.ndarray\' obje'
        'ct has no attribute \'figure\'"\n'
        'plots.cantilever.ModeShapesFigure(ax=empty) -> AttributeError: "\'numpy.ndarray\' o'
        'bject has no attribute \'figure\'"\n'
        'plots.cantilever.ModeShapesFigure(ax=nan-array) -> AttributeError: "\'numpy.ndarra'
        'y\' object has no attribute \'figure\'"'
    ), False),
    'plots.cantilever.mode_shapes_figure:ax': ((
        'plots.cantilever.mode_shapes_figure(ax=nan) -> AttributeError: "\'float\' object ha'
        's no attribute \'figure\'"\n'
        'plots.cantilever.mode_shapes_figure(ax=inf) -> AttributeError: "\'float\' object ha'
        's no attribute \'figure\'"\n'
        'plots.cantilever.mode_shapes_figure(ax=-inf) -> AttributeError: "\'float\' object h'
        'as no attribute \'figure\'"\n'
        'plots.cantilever.mode_shapes_figure(ax=str) -> AttributeError: "\'str\' object has '
        'no attribute \'figure\'"\n'
        'plots.cantilever.mode_shapes_figure(ax=bool) -> AttributeError: "\'bool\' object ha'
        's no attribute \'figure\'"\n'
        'plots.cantilever.mode_shapes_figure(ax=complex) -> AttributeError: "\'complex\' obj'
        'ect has no attribute \'figure\'"\n'
        'plots.cantilever.mode_shapes_figure(ax=list) -> AttributeError: "\'list\' object ha'
        's no attribute \'figure\'"\n'
        'plots.cantilever.mode_shapes_figure(ax=object) -> AttributeError: "\'Foreign\' obje'
        'ct has no attribute \'figure\'"\n'
        'plots.cantilever.mode_shapes_figure(ax=zero) -> AttributeError: "\'float\' object h'
        'as no attribute \'figure\'"\n'
        'plots.cantilever.mode_shapes_figure(ax=negative) -> AttributeError: "\'float\' obje'
        'ct has no attribute \'figure\'"\n'
        'plots.cantilever.mode_shapes_figure(ax=huge) -> AttributeError: "\'float\' object h'
        'as no attribute \'figure\'"\n'
        'plots.cantilever.mode_shapes_figure(ax=-huge) -> AttributeError: "\'float\' object '
        'has no attribute \'figure\'"\n'
        'plots.cantilever.mode_shapes_figure(ax=tiny) -> AttributeError: "\'float\' object h'
        'as no attribute \'figure\'"\n'
        'plots.cantilever.mode_shapes_figure(ax=bigint) -> AttributeError: "\'int\' object h'
        'as no attribute \'figure\'"\n'
        'plots.cantilever.mode_shapes_figure(ax=hugeint) -> AttributeError: "\'int\' object '
        'has no attribute \'figure\'"\n'
        'plots.cantilever.mode_shapes_figure(ax=2d) -> AttributeError: "\'numpy.ndarray\' ob'
        'ject has no attribute \'figure\'"\n'
        'plots.cantilever.mode_shapes_figure(ax=empty) -> AttributeError: "\'numpy.ndarray\''
        ' object has no attribute \'figure\'"\n'
        'plots.cantilever.mode_shapes_figure(ax=nan-array) -> AttributeError: "\'numpy.ndar'
        'ray\' object has no attribute \'figure\'"'
    ), False),
    'plots.contact.contact_curves:extent': ((
        'plots.contact.contact_curves(extent=huge) -> returned non-finite (rho_nm: array with '
        '200 non-finite of 243)'
    ), False),
    'plots.contact.fit_figure:zoom': ((
        'plots.contact.fit_figure(zoom=None) -> accepted silently'
    ), False),
    'plots.contact.tip_geometries_figure:height': ((
        "plots.contact.tip_geometries_figure(height=huge) -> LinAlgError not naming height: 'S"
        "ingular matrix'"
    ), False),
    'plots.contact.tip_geometries_figure:tips': ((
        'plots.contact.tip_geometries_figure(tips=nan) -> TypeError not naming tips: "\'flo'
        'at\' object is not iterable"\n'
        'plots.contact.tip_geometries_figure(tips=inf) -> TypeError not naming tips: "\'flo'
        'at\' object is not iterable"\n'
        'plots.contact.tip_geometries_figure(tips=-inf) -> TypeError not naming tips: "\'fl'
        'oat\' object is not iterable"\n'
        'plots.contact.tip_geometries_figure(tips=str) -> AttributeError: "\'str\' object ha'
        's no attribute \'outline\'"\n'
        'plots.contact.tip_geometries_figure(tips=bool) -> TypeError not naming tips: "\'bo'
        'ol\' object is not iterable"\n'
        'plots.contact.tip_geometries_figure(tips=complex) -> TypeError not naming tips: "'
        '\'complex\' object is not iterable"\n'
        'plots.contact.tip_geometries_figure(tips=list) -> AttributeError: "\'float\' object'
        ' has no attribute \'outline\'"\n'
        'plots.contact.tip_geometries_figure(tips=object) -> TypeError not naming tips: "\''
        'Foreign\' object is not iterable"\n'
        'plots.contact.tip_geometries_figure(tips=zero) -> TypeError not naming tips: "\'fl'
        'oat\' object is not iterable"\n'
        'plots.contact.tip_geometries_figure(tips=negative) -> TypeError not naming tips: '
        '"\'float\' object is not iterable"\n'
        'plots.contact.tip_geometries_figure(tips=huge) -> TypeError not naming tips: "\'fl'
        'oat\' object is not iterable"\n'
        'plots.contact.tip_geometries_figure(tips=-huge) -> TypeError not naming tips: "\'f'
        'loat\' object is not iterable"\n'
        'plots.contact.tip_geometries_figure(tips=tiny) -> TypeError not naming tips: "\'fl'
        'oat\' object is not iterable"\n'
        'plots.contact.tip_geometries_figure(tips=bigint) -> TypeError not naming tips: "\''
        'int\' object is not iterable"\n'
        'plots.contact.tip_geometries_figure(tips=hugeint) -> TypeError not naming tips: "'
        '\'int\' object is not iterable"\n'
        'plots.contact.tip_geometries_figure(tips=2d) -> AttributeError: "\'numpy.ndarray\' '
        'object has no attribute \'outline\'"\n'
        "plots.contact.tip_geometries_figure(tips=empty) -> ValueError not naming tips: 'Numbe"
        "r of columns must be a positive integer, not 0'\n"
        'plots.contact.tip_geometries_figure(tips=nan-array) -> AttributeError: "\'numpy.fl'
        'oat64\' object has no attribute \'outline\'"'
    ), False),
    'plots.controller.ScanFigure:title': ((
        'plots.controller.ScanFigure(title=nan) -> accepted silently\n'
        'plots.controller.ScanFigure(title=None) -> accepted silently\n'
        'plots.controller.ScanFigure(title=str) -> accepted silently\n'
        'plots.controller.ScanFigure(title=bool) -> accepted silently\n'
        'plots.controller.ScanFigure(title=complex) -> accepted silently\n'
        'plots.controller.ScanFigure(title=object) -> accepted silently\n'
        "plots.controller.ScanFigure(title=2d) -> ValueError not naming title: 'The truth valu"
        "e of an array with more than one element is ambiguous. Use a.any() or a.all(...'\n"
        "plots.controller.ScanFigure(title=empty) -> ValueError not naming title: 'The truth v"
        "alue of an empty array is ambiguous. Use `array.size > 0` to check that an arra...'\n"
        "plots.controller.ScanFigure(title=nan-array) -> ValueError not naming title: 'The tru"
        'th value of an array with more than one element is ambiguous. Use a.any() or a.all(..'
        ".'"
    ), False),
    'plots.controller.fig4_figure:presets': ((
        'plots.controller.fig4_figure(presets=nan) -> TypeError not naming presets: "object of'
        ' type \'float\' has no len()"\n'
        'plots.controller.fig4_figure(presets=inf) -> TypeError not naming presets: "object of'
        ' type \'float\' has no len()"\n'
        'plots.controller.fig4_figure(presets=-inf) -> TypeError not naming presets: "object o'
        'f type \'float\' has no len()"\n'
        'plots.controller.fig4_figure(presets=str) -> AttributeError: "\'str\' object has no'
        ' attribute \'values\'"\n'
        'plots.controller.fig4_figure(presets=bool) -> TypeError not naming presets: "object o'
        'f type \'bool\' has no len()"\n'
        'plots.controller.fig4_figure(presets=complex) -> TypeError not naming presets: "objec'
        't of type \'complex\' has no len()"\n'
        'plots.controller.fig4_figure(presets=list) -> AttributeError: "\'list\' object has '
        'no attribute \'values\'"\n'
        'plots.controller.fig4_figure(presets=object) -> TypeError not naming presets: "object'
        ' of type \'Foreign\' has no len()"\n'
        'plots.controller.fig4_figure(presets=zero) -> TypeError not naming presets: "object o'
        'f type \'float\' has no len()"\n'
        'plots.controller.fig4_figure(presets=negative) -> TypeError not naming presets: "obje'
        'ct of type \'float\' has no len()"\n'
        'plots.controller.fig4_figure(presets=huge) -> TypeError not naming presets: "object o'
        'f type \'float\' has no len()"\n'
        'plots.controller.fig4_figure(presets=-huge) -> TypeError not naming presets: "object '
        'of type \'float\' has no len()"\n'
        'plots.controller.fig4_figure(presets=tiny) -> TypeError not naming presets: "object o'
        'f type \'float\' has no len()"\n'
        'plots.controller.fig4_figure(presets=bigint) -> TypeError not naming presets: "object'
        ' of type \'int\' has no len()"\n'
        'plots.controller.fig4_figure(presets=hugeint) -> TypeError not naming presets: "objec'
        't of type \'int\' has no len()"\n'
        'plots.controller.fig4_figure(presets=2d) -> AttributeError: "\'numpy.ndarray\' obje'
        'ct has no attribute \'values\'"\n'
        "plots.controller.fig4_figure(presets=empty) -> ValueError not naming presets: 'Number"
        " of rows must be a positive integer, not 0'\n"
        'plots.controller.fig4_figure(presets=nan-array) -> AttributeError: "\'numpy.ndarra'
        'y\' object has no attribute \'values\'"'
    ), False),
    'plots.controller.image_figure:signal': ((
        "plots.controller.image_figure(signal=2d) -> ValueError not naming signal: 'The truth "
        'value of an array with more than one element is ambiguous. Use a.any() or a.all(.'
        "..'\n"
        "plots.controller.image_figure(signal=empty) -> ValueError not naming signal: 'The tru"
        'th value of an empty array is ambiguous. Use `array.size > 0` to check that an arra..'
        ".'\n"
        "plots.controller.image_figure(signal=nan-array) -> ValueError not naming signal: 'The"
        ' truth value of an array with more than one element is ambiguous. Use a.any() or a.al'
        "l(...'"
    ), False),
    'plots.controller.polygon_figure:height': ((
        "plots.controller.polygon_figure(height=list) -> ValueError not naming height: 'x and "
        "y must have same first dimension, but have shapes (12,) and (2,)'\n"
        "plots.controller.polygon_figure(height=empty) -> ValueError not naming height: 'x and"
        " y must have same first dimension, but have shapes (12,) and (0,)'...'"
    ), False),
    'plots.controller.polygon_figure:n_show': ((
        "plots.controller.polygon_figure(n_show=nan) -> TypeError not naming n_show: 'slice in"
        "dices must be integers or None or have an __index__ method'\n"
        "plots.controller.polygon_figure(n_show=inf) -> TypeError not naming n_show: 'slice in"
        "dices must be integers or None or have an __index__ method'\n"
        "plots.controller.polygon_figure(n_show=-inf) -> TypeError not naming n_show: 'slice i"
        "ndices must be integers or None or have an __index__ method'\n"
        'plots.controller.polygon_figure(n_show=None) -> accepted silently\n'
        "plots.controller.polygon_figure(n_show=str) -> TypeError not naming n_show: 'slice in"
        "dices must be integers or None or have an __index__ method'\n"
        'plots.controller.polygon_figure(n_show=bool) -> accepted silently\n'
        "plots.controller.polygon_figure(n_show=complex) -> TypeError not naming n_show: 'slic"
        "e indices must be integers or None or have an __index__ method'\n"
        "plots.controller.polygon_figure(n_show=list) -> TypeError not naming n_show: 'slice i"
        "ndices must be integers or None or have an __index__ method'\n"
        "plots.controller.polygon_figure(n_show=object) -> TypeError not naming n_show: 'slice"
        " indices must be integers or None or have an __index__ method'\n"
        "plots.controller.polygon_figure(n_show=zero) -> TypeError not naming n_show: 'slice i"
        "ndices must be integers or None or have an __index__ method'\n"
        "plots.controller.polygon_figure(n_show=negative) -> TypeError not naming n_show: 'sli"
        "ce indices must be integers or None or have an __index__ method'\n"
        "plots.controller.polygon_figure(n_show=huge) -> TypeError not naming n_show: 'slice i"
        "ndices must be integers or None or have an __index__ method'\n"
        "plots.controller.polygon_figure(n_show=-huge) -> TypeError not naming n_show: 'slice "
        "indices must be integers or None or have an __index__ method'\n"
        "plots.controller.polygon_figure(n_show=tiny) -> TypeError not naming n_show: 'slice i"
        "ndices must be integers or None or have an __index__ method'\n"
        "plots.controller.polygon_figure(n_show=2d) -> TypeError not naming n_show: 'only inte"
        "ger scalar arrays can be converted to a scalar index'\n"
        "plots.controller.polygon_figure(n_show=empty) -> TypeError not naming n_show: 'only i"
        "nteger scalar arrays can be converted to a scalar index'\n"
        "plots.controller.polygon_figure(n_show=nan-array) -> TypeError not naming n_show: 'on"
        "ly integer scalar arrays can be converted to a scalar index'"
    ), False),
    'plots.hardware.comparison_view:comparison': ((
        'plots.hardware.comparison_view(valid arguments) -> returned non-finite (reference: ar'
        'ray with 4 non-finite of 4, 4 NaN)'
    ), False),
    'plots.hardware.comparison_view:z_step': ((
        'plots.hardware.comparison_view(valid arguments) -> returned non-finite (reference: ar'
        'ray with 4 non-finite of 4, 4 NaN)'
    ), False),
    'plots.imaging.ImagingFigure:cmap': ((
        'plots.imaging.ImagingFigure(cmap=None) -> accepted silently\n'
        'plots.imaging.ImagingFigure(cmap=list) -> TypeError not naming cmap: "unhashable type'
        ': \'list\'"\n'
        'plots.imaging.ImagingFigure(cmap=2d) -> TypeError not naming cmap: "unhashable type: '
        '\'numpy.ndarray\'"\n'
        'plots.imaging.ImagingFigure(cmap=empty) -> TypeError not naming cmap: "unhashable typ'
        'e: \'numpy.ndarray\'"\n'
        'plots.imaging.ImagingFigure(cmap=nan-array) -> TypeError not naming cmap: "unhashable'
        ' type: \'numpy.ndarray\'"'
    ), False),
    'plots.imaging.scan_view:status': ((
        'plots.imaging.scan_view(status=nan) -> accepted silently\n'
        'plots.imaging.scan_view(status=str) -> accepted silently\n'
        'plots.imaging.scan_view(status=bool) -> accepted silently\n'
        'plots.imaging.scan_view(status=complex) -> accepted silently\n'
        'plots.imaging.scan_view(status=object) -> accepted silently\n'
        'plots.imaging.scan_view(status=nan-array) -> accepted silently'
    ), False),
    'plots.modes.ForceVolumeFigure:names': ((
        'plots.modes.ForceVolumeFigure(names=nan) -> TypeError not naming names: "\'float\' '
        'object is not iterable"\n'
        'plots.modes.ForceVolumeFigure(names=inf) -> TypeError not naming names: "\'float\' '
        'object is not iterable"\n'
        'plots.modes.ForceVolumeFigure(names=-inf) -> TypeError not naming names: "\'float\''
        ' object is not iterable"\n'
        'plots.modes.ForceVolumeFigure(names=bool) -> TypeError not naming names: "\'bool\' '
        'object is not iterable"\n'
        'plots.modes.ForceVolumeFigure(names=complex) -> TypeError not naming names: "\'com'
        'plex\' object is not iterable"\n'
        'plots.modes.ForceVolumeFigure(names=object) -> TypeError not naming names: "\'Fore'
        'ign\' object is not iterable"\n'
        'plots.modes.ForceVolumeFigure(names=zero) -> TypeError not naming names: "\'float\''
        ' object is not iterable"\n'
        'plots.modes.ForceVolumeFigure(names=negative) -> TypeError not naming names: "\'fl'
        'oat\' object is not iterable"\n'
        'plots.modes.ForceVolumeFigure(names=huge) -> TypeError not naming names: "\'float\''
        ' object is not iterable"\n'
        'plots.modes.ForceVolumeFigure(names=-huge) -> TypeError not naming names: "\'float'
        '\' object is not iterable"\n'
        'plots.modes.ForceVolumeFigure(names=tiny) -> TypeError not naming names: "\'float\''
        ' object is not iterable"\n'
        'plots.modes.ForceVolumeFigure(names=bigint) -> TypeError not naming names: "\'int\''
        ' object is not iterable"\n'
        'plots.modes.ForceVolumeFigure(names=hugeint) -> TypeError not naming names: "\'int'
        '\' object is not iterable"\n'
        'plots.modes.ForceVolumeFigure(names=nan-array) -> accepted silently'
    ), False),
    'plots.modes.LateralFigure:row': ((
        'plots.modes.LateralFigure(row=nan) -> accepted silently\n'
        'plots.modes.LateralFigure(row=str) -> accepted silently\n'
        'plots.modes.LateralFigure(row=bool) -> accepted silently\n'
        'plots.modes.LateralFigure(row=complex) -> accepted silently\n'
        'plots.modes.LateralFigure(row=object) -> accepted silently\n'
        'plots.modes.LateralFigure(row=nan-array) -> accepted silently'
    ), False),
    'plots.modes.TappingFigure:jumps': ((
        'plots.modes.TappingFigure(jumps=nan) -> AttributeError: "\'float\' object has no at'
        'tribute \'get\'"\n'
        'plots.modes.TappingFigure(jumps=inf) -> AttributeError: "\'float\' object has no at'
        'tribute \'get\'"\n'
        'plots.modes.TappingFigure(jumps=-inf) -> AttributeError: "\'float\' object has no a'
        'ttribute \'get\'"\n'
        'plots.modes.TappingFigure(jumps=str) -> AttributeError: "\'str\' object has no attr'
        'ibute \'get\'"\n'
        'plots.modes.TappingFigure(jumps=bool) -> AttributeError: "\'bool\' object has no at'
        'tribute \'get\'"\n'
        'plots.modes.TappingFigure(jumps=complex) -> AttributeError: "\'complex\' object has'
        ' no attribute \'get\'"\n'
        'plots.modes.TappingFigure(jumps=list) -> AttributeError: "\'list\' object has no at'
        'tribute \'get\'"\n'
        'plots.modes.TappingFigure(jumps=object) -> AttributeError: "\'Foreign\' object has '
        'no attribute \'get\'"\n'
        'plots.modes.TappingFigure(jumps=zero) -> AttributeError: "\'float\' object has no a'
        'ttribute \'get\'"\n'
        'plots.modes.TappingFigure(jumps=negative) -> AttributeError: "\'float\' object has '
        'no attribute \'get\'"\n'
        'plots.modes.TappingFigure(jumps=huge) -> AttributeError: "\'float\' object has no a'
        'ttribute \'get\'"\n'
        'plots.modes.TappingFigure(jumps=-huge) -> AttributeError: "\'float\' object has no '
        'attribute \'get\'"\n'
        'plots.modes.TappingFigure(jumps=tiny) -> AttributeError: "\'float\' object has no a'
        'ttribute \'get\'"\n'
        'plots.modes.TappingFigure(jumps=bigint) -> AttributeError: "\'int\' object has no a'
        'ttribute \'get\'"\n'
        'plots.modes.TappingFigure(jumps=hugeint) -> AttributeError: "\'int\' object has no '
        'attribute \'get\'"\n'
        'plots.modes.TappingFigure(jumps=2d) -> AttributeError: "\'numpy.ndarray\' object ha'
        's no attribute \'get\'"\n'
        'plots.modes.TappingFigure(jumps=empty) -> AttributeError: "\'numpy.ndarray\' object'
        ' has no attribute \'get\'"\n'
        'plots.modes.TappingFigure(jumps=nan-array) -> AttributeError: "\'numpy.ndarray\' ob'
        'ject has no attribute \'get\'"'
    ), False),
    'plots.modes.TappingFigure:setpoint': ((
        "plots.modes.TappingFigure(setpoint=nan) -> TypeError not naming setpoint: 'cannot unp"
        "ack non-iterable float object'\n"
        "plots.modes.TappingFigure(setpoint=inf) -> TypeError not naming setpoint: 'cannot unp"
        "ack non-iterable float object'\n"
        "plots.modes.TappingFigure(setpoint=-inf) -> TypeError not naming setpoint: 'cannot un"
        "pack non-iterable float object'\n"
        "plots.modes.TappingFigure(setpoint=str) -> ValueError not naming setpoint: 'not enoug"
        "h values to unpack (expected 5, got 4)'\n"
        "plots.modes.TappingFigure(setpoint=bool) -> TypeError not naming setpoint: 'cannot un"
        "pack non-iterable bool object'\n"
        "plots.modes.TappingFigure(setpoint=complex) -> TypeError not naming setpoint: 'cannot"
        " unpack non-iterable complex object'\n"
        "plots.modes.TappingFigure(setpoint=list) -> ValueError not naming setpoint: 'not enou"
        "gh values to unpack (expected 5, got 2)'\n"
        "plots.modes.TappingFigure(setpoint=object) -> TypeError not naming setpoint: 'cannot "
        "unpack non-iterable Foreign object'\n"
        "plots.modes.TappingFigure(setpoint=zero) -> TypeError not naming setpoint: 'cannot un"
        "pack non-iterable float object'\n"
        "plots.modes.TappingFigure(setpoint=negative) -> TypeError not naming setpoint: 'canno"
        "t unpack non-iterable float object'\n"
        "plots.modes.TappingFigure(setpoint=huge) -> TypeError not naming setpoint: 'cannot un"
        "pack non-iterable float object'\n"
        "plots.modes.TappingFigure(setpoint=-huge) -> TypeError not naming setpoint: 'cannot u"
        "npack non-iterable float object'\n"
        "plots.modes.TappingFigure(setpoint=tiny) -> TypeError not naming setpoint: 'cannot un"
        "pack non-iterable float object'\n"
        "plots.modes.TappingFigure(setpoint=bigint) -> TypeError not naming setpoint: 'cannot "
        "unpack non-iterable int object'\n"
        "plots.modes.TappingFigure(setpoint=hugeint) -> TypeError not naming setpoint: 'cannot"
        " unpack non-iterable int object'\n"
        "plots.modes.TappingFigure(setpoint=2d) -> ValueError not naming setpoint: 'not enough"
        " values to unpack (expected 5, got 3)'\n"
        "plots.modes.TappingFigure(setpoint=empty) -> ValueError not naming setpoint: 'not eno"
        "ugh values to unpack (expected 5, got 0)'\n"
        "plots.modes.TappingFigure(setpoint=nan-array) -> ValueError not naming setpoint: 'not"
        " enough values to unpack (expected 5, got 2)'"
    ), False),
    'scenes.camera.show_helpers:axes': ((
        'scenes.camera.show_helpers(axes=nan) -> accepted silently\n'
        'scenes.camera.show_helpers(axes=None) -> accepted silently\n'
        'scenes.camera.show_helpers(axes=str) -> accepted silently\n'
        'scenes.camera.show_helpers(axes=complex) -> accepted silently\n'
        'scenes.camera.show_helpers(axes=object) -> accepted silently\n'
        "scenes.camera.show_helpers(axes=2d) -> ValueError not naming axes: 'The truth value o"
        "f an array with more than one element is ambiguous. Use a.any() or a.all(...'\n"
        "scenes.camera.show_helpers(axes=empty) -> ValueError not naming axes: 'The truth valu"
        "e of an empty array is ambiguous. Use `array.size > 0` to check that an arra...'\n"
        "scenes.camera.show_helpers(axes=nan-array) -> ValueError not naming axes: 'The truth "
        "value of an array with more than one element is ambiguous. Use a.any() or a.all(...'"
    ), False),
    'scenes.camera.show_helpers:grid': ((
        'scenes.camera.show_helpers(grid=nan) -> accepted silently\n'
        'scenes.camera.show_helpers(grid=None) -> accepted silently\n'
        'scenes.camera.show_helpers(grid=str) -> accepted silently\n'
        'scenes.camera.show_helpers(grid=complex) -> accepted silently\n'
        'scenes.camera.show_helpers(grid=object) -> accepted silently\n'
        "scenes.camera.show_helpers(grid=2d) -> ValueError not naming grid: 'The truth value o"
        "f an array with more than one element is ambiguous. Use a.any() or a.all(...'\n"
        "scenes.camera.show_helpers(grid=empty) -> ValueError not naming grid: 'The truth valu"
        "e of an empty array is ambiguous. Use `array.size > 0` to check that an arra...'\n"
        "scenes.camera.show_helpers(grid=nan-array) -> ValueError not naming grid: 'The truth "
        "value of an array with more than one element is ambiguous. Use a.any() or a.all(...'"
    ), False),
    'scenes.cantilever.CantileverScene:camera': ((
        'scenes.cantilever.CantileverScene(camera=nan) -> accepted silently\n'
        'scenes.cantilever.CantileverScene(camera=None) -> accepted silently\n'
        'scenes.cantilever.CantileverScene(camera=str) -> accepted silently\n'
        'scenes.cantilever.CantileverScene(camera=complex) -> accepted silently\n'
        'scenes.cantilever.CantileverScene(camera=object) -> accepted silently\n'
        "scenes.cantilever.CantileverScene(camera=2d) -> ValueError not naming camera: 'The tr"
        'uth value of an array with more than one element is ambiguous. Use a.any() or a.all(.'
        "..'\n"
        "scenes.cantilever.CantileverScene(camera=empty) -> ValueError not naming camera: 'The"
        ' truth value of an empty array is ambiguous. Use `array.size > 0` to check that an ar'
        "ra...'\n"
        'scenes.cantilever.CantileverScene(camera=nan-array) -> ValueError not naming camera: '
        "'The truth value of an array with more than one element is ambiguous. Use a.any() or "
        "a.all(...'"
    ), False),
    'scenes.cantilever.CantileverScene:path': ((
        'scenes.cantilever.CantileverScene(path=str) -> accepted silently'
    ), False),
    'scenes.contact.ContactScene:camera': ((
        'scenes.contact.ContactScene(camera=nan) -> accepted silently\n'
        'scenes.contact.ContactScene(camera=None) -> accepted silently\n'
        'scenes.contact.ContactScene(camera=str) -> accepted silently\n'
        'scenes.contact.ContactScene(camera=complex) -> accepted silently\n'
        'scenes.contact.ContactScene(camera=object) -> accepted silently\n'
        "scenes.contact.ContactScene(camera=2d) -> ValueError not naming camera: 'The truth va"
        "lue of an array with more than one element is ambiguous. Use a.any() or a.all(...'\n"
        "scenes.contact.ContactScene(camera=empty) -> ValueError not naming camera: 'The truth"
        " value of an empty array is ambiguous. Use `array.size > 0` to check that an arra...'"
        '\n'
        "scenes.contact.ContactScene(camera=nan-array) -> ValueError not naming camera: 'The t"
        'ruth value of an array with more than one element is ambiguous. Use a.any() or a.all('
        "...'"
    ), False),
    'scenes.contact.ContactScene:extent': ((
        "scenes.contact.ContactScene(extent=huge) -> ValueError not naming extent: 'points mus"
        "t be finite, got -inf (at index 2)'\n"
        "scenes.contact.ContactScene(extent=tiny) -> ValueError not naming extent: 'the camera"
        " must look at a target other than its position, not straight up or down; got pos...'"
    ), False),
    'scenes.contact.ContactScene:path': ((
        'scenes.contact.ContactScene(path=nan) -> AttributeError: "\'float\' object has no a'
        'ttribute \'split\'"\n'
        'scenes.contact.ContactScene(path=inf) -> AttributeError: "\'float\' object has no a'
        'ttribute \'split\'"\n'
        'scenes.contact.ContactScene(path=-inf) -> AttributeError: "\'float\' object has no '
        'attribute \'split\'"\n'
        'scenes.contact.ContactScene(path=None) -> AttributeError: "\'NoneType\' object has '
        'no attribute \'split\'"\n'
        'scenes.contact.ContactScene(path=str) -> accepted silently\n'
        'scenes.contact.ContactScene(path=bool) -> AttributeError: "\'bool\' object has no a'
        'ttribute \'split\'"\n'
        'scenes.contact.ContactScene(path=complex) -> AttributeError: "\'complex\' object ha'
        's no attribute \'split\'"\n'
        'scenes.contact.ContactScene(path=list) -> AttributeError: "\'list\' object has no a'
        'ttribute \'split\'"\n'
        'scenes.contact.ContactScene(path=object) -> AttributeError: "\'Foreign\' object has'
        ' no attribute \'split\'"\n'
        'scenes.contact.ContactScene(path=zero) -> AttributeError: "\'float\' object has no '
        'attribute \'split\'"\n'
        'scenes.contact.ContactScene(path=negative) -> AttributeError: "\'float\' object has'
        ' no attribute \'split\'"\n'
        'scenes.contact.ContactScene(path=huge) -> AttributeError: "\'float\' object has no '
        'attribute \'split\'"\n'
        'scenes.contact.ContactScene(path=-huge) -> AttributeError: "\'float\' object has no'
        ' attribute \'split\'"\n'
        'scenes.contact.ContactScene(path=tiny) -> AttributeError: "\'float\' object has no '
        'attribute \'split\'"\n'
        'scenes.contact.ContactScene(path=bigint) -> AttributeError: "\'int\' object has no '
        'attribute \'split\'"\n'
        'scenes.contact.ContactScene(path=hugeint) -> AttributeError: "\'int\' object has no'
        ' attribute \'split\'"\n'
        'scenes.contact.ContactScene(path=2d) -> AttributeError: "\'numpy.ndarray\' object h'
        'as no attribute \'split\'"\n'
        'scenes.contact.ContactScene(path=empty) -> AttributeError: "\'numpy.ndarray\' objec'
        't has no attribute \'split\'"\n'
        'scenes.contact.ContactScene(path=nan-array) -> AttributeError: "\'numpy.ndarray\' o'
        'bject has no attribute \'split\'"'
    ), False),
    'scenes.contact.ContactScene:unit': ((
        "scenes.contact.ContactScene(unit=huge) -> ValueError not naming unit: 'the camera mus"
        "t look at a target other than its position, not straight up or down; got pos...'\n"
        "scenes.contact.ContactScene(unit=tiny) -> ValueError not naming unit: 'points must be"
        " finite, got -inf (at index 2)'"
    ), False),
    'scenes.contact.surface_mesh:extent': ((
        "scenes.contact.surface_mesh(extent=huge) -> ValueError not naming extent: 'heights, p"
        "ixel sizes and origin divided by unit must stay below 3.4e+38 scene units, got i...'"
    ), False),
    'scenes.contact.surface_mesh:half': ((
        'scenes.contact.surface_mesh(half=nan) -> accepted silently\n'
        'scenes.contact.surface_mesh(half=None) -> accepted silently\n'
        'scenes.contact.surface_mesh(half=str) -> accepted silently\n'
        'scenes.contact.surface_mesh(half=complex) -> accepted silently\n'
        'scenes.contact.surface_mesh(half=object) -> accepted silently\n'
        "scenes.contact.surface_mesh(half=2d) -> ValueError not naming half: 'The truth value "
        "of an array with more than one element is ambiguous. Use a.any() or a.all(...'\n"
        "scenes.contact.surface_mesh(half=empty) -> ValueError not naming half: 'The truth val"
        "ue of an empty array is ambiguous. Use `array.size > 0` to check that an arra...'\n"
        "scenes.contact.surface_mesh(half=nan-array) -> ValueError not naming half: 'The truth"
        " value of an array with more than one element is ambiguous. Use a.any() or a.all(...'"
    ), False),
    'scenes.contact.tip_mesh:half': ((
        'scenes.contact.tip_mesh(half=nan) -> accepted silently\n'
        'scenes.contact.tip_mesh(half=None) -> accepted silently\n'
        'scenes.contact.tip_mesh(half=str) -> accepted silently\n'
        'scenes.contact.tip_mesh(half=complex) -> accepted silently\n'
        'scenes.contact.tip_mesh(half=object) -> accepted silently\n'
        "scenes.contact.tip_mesh(half=2d) -> ValueError not naming half: 'The truth value of a"
        "n array with more than one element is ambiguous. Use a.any() or a.all(...'\n"
        "scenes.contact.tip_mesh(half=empty) -> ValueError not naming half: 'The truth value o"
        "f an empty array is ambiguous. Use `array.size > 0` to check that an arra...'\n"
        "scenes.contact.tip_mesh(half=nan-array) -> ValueError not naming half: 'The truth val"
        "ue of an array with more than one element is ambiguous. Use a.any() or a.all(...'"
    ), False),
    'scenes.contact.tip_mesh:height': ((
        'scenes.contact.tip_mesh(height=huge) -> returned non-finite (0: array with 17161 non-'
        'finite of 17286)'
    ), False),
    'scenes.contact.tip_mesh:unit': ((
        'scenes.contact.tip_mesh(unit=tiny) -> returned non-finite (0: array with 17161 non-fi'
        'nite of 17286)'
    ), False),
    'scenes.imaging.ImagingScene:camera': ((
        'scenes.imaging.ImagingScene(camera=nan) -> accepted silently\n'
        'scenes.imaging.ImagingScene(camera=None) -> accepted silently\n'
        'scenes.imaging.ImagingScene(camera=str) -> accepted silently\n'
        'scenes.imaging.ImagingScene(camera=complex) -> accepted silently\n'
        'scenes.imaging.ImagingScene(camera=object) -> accepted silently\n'
        "scenes.imaging.ImagingScene(camera=2d) -> ValueError not naming camera: 'The truth va"
        "lue of an array with more than one element is ambiguous. Use a.any() or a.all(...'\n"
        "scenes.imaging.ImagingScene(camera=empty) -> ValueError not naming camera: 'The truth"
        " value of an empty array is ambiguous. Use `array.size > 0` to check that an arra...'"
        '\n'
        "scenes.imaging.ImagingScene(camera=nan-array) -> ValueError not naming camera: 'The t"
        'ruth value of an array with more than one element is ambiguous. Use a.any() or a.all('
        "...'"
    ), False),
    'scenes.imaging.ImagingScene:exaggeration': ((
        'scenes.imaging.ImagingScene(exaggeration=huge) -> ValueError not naming exaggeration:'
        " 'heights, pixel sizes and origin divided by unit must stay below 3.4e+38 scene units"
        ", got 8...'"
    ), False),
    'scenes.imaging.ImagingScene:path': ((
        'scenes.imaging.ImagingScene(path=nan) -> AttributeError: "\'float\' object has no a'
        'ttribute \'split\'"\n'
        'scenes.imaging.ImagingScene(path=inf) -> AttributeError: "\'float\' object has no a'
        'ttribute \'split\'"\n'
        'scenes.imaging.ImagingScene(path=-inf) -> AttributeError: "\'float\' object has no '
        'attribute \'split\'"\n'
        'scenes.imaging.ImagingScene(path=None) -> AttributeError: "\'NoneType\' object has '
        'no attribute \'split\'"\n'
        'scenes.imaging.ImagingScene(path=str) -> accepted silently\n'
        'scenes.imaging.ImagingScene(path=bool) -> AttributeError: "\'bool\' object has no a'
        'ttribute \'split\'"\n'
        'scenes.imaging.ImagingScene(path=complex) -> AttributeError: "\'complex\' object ha'
        's no attribute \'split\'"\n'
        'scenes.imaging.ImagingScene(path=list) -> AttributeError: "\'list\' object has no a'
        'ttribute \'split\'"\n'
        'scenes.imaging.ImagingScene(path=object) -> AttributeError: "\'Foreign\' object has'
        ' no attribute \'split\'"\n'
        'scenes.imaging.ImagingScene(path=zero) -> AttributeError: "\'float\' object has no '
        'attribute \'split\'"\n'
        'scenes.imaging.ImagingScene(path=negative) -> AttributeError: "\'float\' object has'
        ' no attribute \'split\'"\n'
        'scenes.imaging.ImagingScene(path=huge) -> AttributeError: "\'float\' object has no '
        'attribute \'split\'"\n'
        'scenes.imaging.ImagingScene(path=-huge) -> AttributeError: "\'float\' object has no'
        ' attribute \'split\'"\n'
        'scenes.imaging.ImagingScene(path=tiny) -> AttributeError: "\'float\' object has no '
        'attribute \'split\'"\n'
        'scenes.imaging.ImagingScene(path=bigint) -> AttributeError: "\'int\' object has no '
        'attribute \'split\'"\n'
        'scenes.imaging.ImagingScene(path=hugeint) -> AttributeError: "\'int\' object has no'
        ' attribute \'split\'"\n'
        'scenes.imaging.ImagingScene(path=2d) -> AttributeError: "\'numpy.ndarray\' object h'
        'as no attribute \'split\'"\n'
        'scenes.imaging.ImagingScene(path=empty) -> AttributeError: "\'numpy.ndarray\' objec'
        't has no attribute \'split\'"\n'
        'scenes.imaging.ImagingScene(path=nan-array) -> AttributeError: "\'numpy.ndarray\' o'
        'bject has no attribute \'split\'"'
    ), False),
    'scenes.imaging.decimation:shape': ((
        'scenes.imaging.decimation(shape=nan) -> TypeError not naming shape: "\'float\' obje'
        'ct is not iterable"\n'
        'scenes.imaging.decimation(shape=inf) -> TypeError not naming shape: "\'float\' obje'
        'ct is not iterable"\n'
        'scenes.imaging.decimation(shape=-inf) -> TypeError not naming shape: "\'float\' obj'
        'ect is not iterable"\n'
        'scenes.imaging.decimation(shape=str) -> ValueError not naming shape: "invalid literal'
        ' for int() with base 10: \'e\'"\n'
        'scenes.imaging.decimation(shape=bool) -> TypeError not naming shape: "\'bool\' obje'
        'ct is not iterable"\n'
        'scenes.imaging.decimation(shape=complex) -> TypeError not naming shape: "\'complex'
        '\' object is not iterable"\n'
        'scenes.imaging.decimation(shape=object) -> TypeError not naming shape: "\'Foreign\''
        ' object is not iterable"\n'
        'scenes.imaging.decimation(shape=zero) -> TypeError not naming shape: "\'float\' obj'
        'ect is not iterable"\n'
        'scenes.imaging.decimation(shape=negative) -> TypeError not naming shape: "\'float\''
        ' object is not iterable"\n'
        'scenes.imaging.decimation(shape=huge) -> TypeError not naming shape: "\'float\' obj'
        'ect is not iterable"\n'
        'scenes.imaging.decimation(shape=-huge) -> TypeError not naming shape: "\'float\' ob'
        'ject is not iterable"\n'
        'scenes.imaging.decimation(shape=tiny) -> TypeError not naming shape: "\'float\' obj'
        'ect is not iterable"\n'
        'scenes.imaging.decimation(shape=bigint) -> TypeError not naming shape: "\'int\' obj'
        'ect is not iterable"\n'
        'scenes.imaging.decimation(shape=hugeint) -> TypeError not naming shape: "\'int\' ob'
        'ject is not iterable"\n'
        "scenes.imaging.decimation(shape=2d) -> TypeError not naming shape: 'only 0-dimensiona"
        "l arrays can be converted to Python scalars'\n"
        "scenes.imaging.decimation(shape=empty) -> ValueError not naming shape: 'not enough va"
        "lues to unpack (expected 2, got 0)'"
    ), False),
    'scenes.legends.TextPlate:text': ((
        'scenes.legends.TextPlate(text=nan) -> accepted silently\n'
        'scenes.legends.TextPlate(text=str) -> accepted silently\n'
        'scenes.legends.TextPlate(text=bool) -> accepted silently\n'
        'scenes.legends.TextPlate(text=complex) -> accepted silently\n'
        'scenes.legends.TextPlate(text=object) -> accepted silently\n'
        'scenes.legends.TextPlate(text=nan-array) -> accepted silently'
    ), False),
    'scenes.legends.colorbar_png:size_px': ((
        'scenes.legends.colorbar_png(size_px=nan) -> TypeError not naming size_px: "\'float'
        '\' object is not subscriptable"\n'
        'scenes.legends.colorbar_png(size_px=inf) -> TypeError not naming size_px: "\'float'
        '\' object is not subscriptable"\n'
        'scenes.legends.colorbar_png(size_px=-inf) -> TypeError not naming size_px: "\'floa'
        't\' object is not subscriptable"\n'
        'scenes.legends.colorbar_png(size_px=None) -> TypeError not naming size_px: "\'None'
        'Type\' object is not subscriptable"\n'
        "scenes.legends.colorbar_png(size_px=str) -> ValueError not naming size_px: 'width_px "
        "must be an integer in [100, 4096], got 1'\n"
        'scenes.legends.colorbar_png(size_px=bool) -> TypeError not naming size_px: "\'bool'
        '\' object is not subscriptable"\n'
        'scenes.legends.colorbar_png(size_px=complex) -> TypeError not naming size_px: "\'c'
        'omplex\' object is not subscriptable"\n'
        "scenes.legends.colorbar_png(size_px=list) -> ValueError not naming size_px: 'width_px"
        " must be an integer in [100, 4096], got 1'\n"
        'scenes.legends.colorbar_png(size_px=object) -> TypeError not naming size_px: "\'Fo'
        'reign\' object is not subscriptable"\n'
        'scenes.legends.colorbar_png(size_px=zero) -> TypeError not naming size_px: "\'floa'
        't\' object is not subscriptable"\n'
        'scenes.legends.colorbar_png(size_px=negative) -> TypeError not naming size_px: "\''
        'float\' object is not subscriptable"\n'
        'scenes.legends.colorbar_png(size_px=huge) -> TypeError not naming size_px: "\'floa'
        't\' object is not subscriptable"\n'
        'scenes.legends.colorbar_png(size_px=-huge) -> TypeError not naming size_px: "\'flo'
        'at\' object is not subscriptable"\n'
        'scenes.legends.colorbar_png(size_px=tiny) -> TypeError not naming size_px: "\'floa'
        't\' object is not subscriptable"\n'
        'scenes.legends.colorbar_png(size_px=bigint) -> TypeError not naming size_px: "\'in'
        't\' object is not subscriptable"\n'
        'scenes.legends.colorbar_png(size_px=hugeint) -> TypeError not naming size_px: "\'i'
        'nt\' object is not subscriptable"\n'
        "scenes.legends.colorbar_png(size_px=2d) -> TypeError not naming size_px: 'only 0-dime"
        "nsional arrays can be converted to Python scalars'\n"
        "scenes.legends.colorbar_png(size_px=empty) -> IndexError: 'index 0 is out of bounds f"
        "or axis 0 with size 0'\n"
        "scenes.legends.colorbar_png(size_px=nan-array) -> ValueError not naming size_px: 'wid"
        "th_px must be an integer in [100, 4096], got 0'"
    ), False),
    'scenes.legends.legend_html:width_px': ((
        'scenes.legends.legend_html(width_px=nan) -> accepted silently\n'
        'scenes.legends.legend_html(width_px=None) -> accepted silently\n'
        'scenes.legends.legend_html(width_px=str) -> accepted silently\n'
        'scenes.legends.legend_html(width_px=bool) -> accepted silently\n'
        'scenes.legends.legend_html(width_px=complex) -> accepted silently\n'
        'scenes.legends.legend_html(width_px=object) -> accepted silently\n'
        'scenes.legends.legend_html(width_px=nan-array) -> accepted silently'
    ), False),
    'scenes.legends.legend_title:exponent': ((
        'scenes.legends.legend_title(exponent=nan) -> accepted silently\n'
        'scenes.legends.legend_title(exponent=None) -> accepted silently\n'
        'scenes.legends.legend_title(exponent=str) -> accepted silently\n'
        'scenes.legends.legend_title(exponent=bool) -> accepted silently\n'
        'scenes.legends.legend_title(exponent=complex) -> accepted silently\n'
        'scenes.legends.legend_title(exponent=object) -> accepted silently\n'
        "scenes.legends.legend_title(exponent=2d) -> ValueError not naming exponent: 'The trut"
        'h value of an array with more than one element is ambiguous. Use a.any() or a.all(...'
        "'\n"
        "scenes.legends.legend_title(exponent=empty) -> ValueError not naming exponent: 'The t"
        'ruth value of an empty array is ambiguous. Use `array.size > 0` to check that an arra'
        "...'\n"
        "scenes.legends.legend_title(exponent=nan-array) -> ValueError not naming exponent: 'T"
        'he truth value of an array with more than one element is ambiguous. Use a.any() or a.'
        "all(...'"
    ), False),
    'scenes.modes.ModesScene:camera': ((
        'scenes.modes.ModesScene(camera=nan) -> accepted silently\n'
        'scenes.modes.ModesScene(camera=None) -> accepted silently\n'
        'scenes.modes.ModesScene(camera=str) -> accepted silently\n'
        'scenes.modes.ModesScene(camera=complex) -> accepted silently\n'
        'scenes.modes.ModesScene(camera=object) -> accepted silently\n'
        "scenes.modes.ModesScene(camera=2d) -> ValueError not naming camera: 'The truth value "
        "of an array with more than one element is ambiguous. Use a.any() or a.all(...'\n"
        "scenes.modes.ModesScene(camera=empty) -> ValueError not naming camera: 'The truth val"
        "ue of an empty array is ambiguous. Use `array.size > 0` to check that an arra...'\n"
        "scenes.modes.ModesScene(camera=nan-array) -> ValueError not naming camera: 'The truth"
        " value of an array with more than one element is ambiguous. Use a.any() or a.all(...'"
    ), False),
    'scenes.modes.ModesScene:path': ((
        'scenes.modes.ModesScene(path=nan) -> AttributeError: "\'float\' object has no attri'
        'bute \'split\'"\n'
        'scenes.modes.ModesScene(path=inf) -> AttributeError: "\'float\' object has no attri'
        'bute \'split\'"\n'
        'scenes.modes.ModesScene(path=-inf) -> AttributeError: "\'float\' object has no attr'
        'ibute \'split\'"\n'
        'scenes.modes.ModesScene(path=None) -> AttributeError: "\'NoneType\' object has no a'
        'ttribute \'split\'"\n'
        'scenes.modes.ModesScene(path=str) -> accepted silently\n'
        'scenes.modes.ModesScene(path=bool) -> AttributeError: "\'bool\' object has no attri'
        'bute \'split\'"\n'
        'scenes.modes.ModesScene(path=complex) -> AttributeError: "\'complex\' object has no'
        ' attribute \'split\'"\n'
        'scenes.modes.ModesScene(path=list) -> AttributeError: "\'list\' object has no attri'
        'bute \'split\'"\n'
        'scenes.modes.ModesScene(path=object) -> AttributeError: "\'Foreign\' object has no '
        'attribute \'split\'"\n'
        'scenes.modes.ModesScene(path=zero) -> AttributeError: "\'float\' object has no attr'
        'ibute \'split\'"\n'
        'scenes.modes.ModesScene(path=negative) -> AttributeError: "\'float\' object has no '
        'attribute \'split\'"\n'
        'scenes.modes.ModesScene(path=huge) -> AttributeError: "\'float\' object has no attr'
        'ibute \'split\'"\n'
        'scenes.modes.ModesScene(path=-huge) -> AttributeError: "\'float\' object has no att'
        'ribute \'split\'"\n'
        'scenes.modes.ModesScene(path=tiny) -> AttributeError: "\'float\' object has no attr'
        'ibute \'split\'"\n'
        'scenes.modes.ModesScene(path=bigint) -> AttributeError: "\'int\' object has no attr'
        'ibute \'split\'"\n'
        'scenes.modes.ModesScene(path=hugeint) -> AttributeError: "\'int\' object has no att'
        'ribute \'split\'"\n'
        'scenes.modes.ModesScene(path=2d) -> AttributeError: "\'numpy.ndarray\' object has n'
        'o attribute \'split\'"\n'
        'scenes.modes.ModesScene(path=empty) -> AttributeError: "\'numpy.ndarray\' object ha'
        's no attribute \'split\'"\n'
        'scenes.modes.ModesScene(path=nan-array) -> AttributeError: "\'numpy.ndarray\' objec'
        't has no attribute \'split\'"'
    ), False),
    'scenes.shapes.Arrow:color': ((
        'scenes.shapes.Arrow(color=nan) -> accepted silently\n'
        'scenes.shapes.Arrow(color=None) -> accepted silently\n'
        'scenes.shapes.Arrow(color=str) -> accepted silently\n'
        'scenes.shapes.Arrow(color=bool) -> accepted silently\n'
        'scenes.shapes.Arrow(color=complex) -> accepted silently\n'
        'scenes.shapes.Arrow(color=object) -> accepted silently\n'
        'scenes.shapes.Arrow(color=nan-array) -> accepted silently'
    ), False),
    'scenes.shapes.Segment:color': ((
        'scenes.shapes.Segment(color=nan) -> accepted silently\n'
        'scenes.shapes.Segment(color=None) -> accepted silently\n'
        'scenes.shapes.Segment(color=str) -> accepted silently\n'
        'scenes.shapes.Segment(color=bool) -> accepted silently\n'
        'scenes.shapes.Segment(color=complex) -> accepted silently\n'
        'scenes.shapes.Segment(color=object) -> accepted silently\n'
        'scenes.shapes.Segment(color=nan-array) -> accepted silently'
    ), False),
    'scenes.shapes.Tube:color': ((
        'scenes.shapes.Tube(color=nan) -> accepted silently\n'
        'scenes.shapes.Tube(color=None) -> accepted silently\n'
        'scenes.shapes.Tube(color=str) -> accepted silently\n'
        'scenes.shapes.Tube(color=bool) -> accepted silently\n'
        'scenes.shapes.Tube(color=complex) -> accepted silently\n'
        'scenes.shapes.Tube(color=object) -> accepted silently\n'
        'scenes.shapes.Tube(color=nan-array) -> accepted silently'
    ), False),
    'scenes.shapes.cone:color': ((
        'scenes.shapes.cone(color=nan) -> accepted silently\n'
        'scenes.shapes.cone(color=None) -> accepted silently\n'
        'scenes.shapes.cone(color=str) -> accepted silently\n'
        'scenes.shapes.cone(color=bool) -> accepted silently\n'
        'scenes.shapes.cone(color=complex) -> accepted silently\n'
        'scenes.shapes.cone(color=object) -> accepted silently\n'
        'scenes.shapes.cone(color=nan-array) -> accepted silently'
    ), False),
    'scenes.shapes.polyline:color': ((
        'scenes.shapes.polyline(color=nan) -> accepted silently\n'
        'scenes.shapes.polyline(color=None) -> accepted silently\n'
        'scenes.shapes.polyline(color=str) -> accepted silently\n'
        'scenes.shapes.polyline(color=bool) -> accepted silently\n'
        'scenes.shapes.polyline(color=complex) -> accepted silently\n'
        'scenes.shapes.polyline(color=object) -> accepted silently\n'
        'scenes.shapes.polyline(color=nan-array) -> accepted silently'
    ), False),
    'scenes.shapes.sphere:color': ((
        'scenes.shapes.sphere(color=nan) -> accepted silently\n'
        'scenes.shapes.sphere(color=None) -> accepted silently\n'
        'scenes.shapes.sphere(color=str) -> accepted silently\n'
        'scenes.shapes.sphere(color=bool) -> accepted silently\n'
        'scenes.shapes.sphere(color=complex) -> accepted silently\n'
        'scenes.shapes.sphere(color=object) -> accepted silently\n'
        'scenes.shapes.sphere(color=nan-array) -> accepted silently'
    ), False),
    'scenes.shapes.sphere:opacity': ((
        'scenes.shapes.sphere(opacity=nan) -> accepted silently\n'
        'scenes.shapes.sphere(opacity=None) -> accepted silently\n'
        'scenes.shapes.sphere(opacity=str) -> accepted silently\n'
        'scenes.shapes.sphere(opacity=bool) -> accepted silently\n'
        'scenes.shapes.sphere(opacity=complex) -> accepted silently\n'
        'scenes.shapes.sphere(opacity=object) -> accepted silently\n'
        'scenes.shapes.sphere(opacity=nan-array) -> accepted silently'
    ), False),
    'scenes.transducers.TransducerScene:camera': ((
        'scenes.transducers.TransducerScene(camera=nan) -> accepted silently\n'
        'scenes.transducers.TransducerScene(camera=None) -> accepted silently\n'
        'scenes.transducers.TransducerScene(camera=str) -> accepted silently\n'
        'scenes.transducers.TransducerScene(camera=complex) -> accepted silently\n'
        'scenes.transducers.TransducerScene(camera=object) -> accepted silently\n'
        "scenes.transducers.TransducerScene(camera=2d) -> ValueError not naming camera: 'The t"
        'ruth value of an array with more than one element is ambiguous. Use a.any() or a.all('
        "...'\n"
        "scenes.transducers.TransducerScene(camera=empty) -> ValueError not naming camera: 'Th"
        'e truth value of an empty array is ambiguous. Use `array.size > 0` to check that an a'
        "rra...'\n"
        'scenes.transducers.TransducerScene(camera=nan-array) -> ValueError not naming camera:'
        " 'The truth value of an array with more than one element is ambiguous. Use a.any() or"
        " a.all(...'"
    ), False),
    'scenes.transducers.TransducerScene:path': ((
        'scenes.transducers.TransducerScene(path=nan) -> AttributeError: "\'float\' object h'
        'as no attribute \'split\'"\n'
        'scenes.transducers.TransducerScene(path=inf) -> AttributeError: "\'float\' object h'
        'as no attribute \'split\'"\n'
        'scenes.transducers.TransducerScene(path=-inf) -> AttributeError: "\'float\' object '
        'has no attribute \'split\'"\n'
        'scenes.transducers.TransducerScene(path=None) -> AttributeError: "\'NoneType\' obje'
        'ct has no attribute \'split\'"\n'
        'scenes.transducers.TransducerScene(path=str) -> accepted silently\n'
        'scenes.transducers.TransducerScene(path=bool) -> AttributeError: "\'bool\' object h'
        'as no attribute \'split\'"\n'
        'scenes.transducers.TransducerScene(path=complex) -> AttributeError: "\'complex\' ob'
        'ject has no attribute \'split\'"\n'
        'scenes.transducers.TransducerScene(path=list) -> AttributeError: "\'list\' object h'
        'as no attribute \'split\'"\n'
        'scenes.transducers.TransducerScene(path=object) -> AttributeError: "\'Foreign\' obj'
        'ect has no attribute \'split\'"\n'
        'scenes.transducers.TransducerScene(path=zero) -> AttributeError: "\'float\' object '
        'has no attribute \'split\'"\n'
        'scenes.transducers.TransducerScene(path=negative) -> AttributeError: "\'float\' obj'
        'ect has no attribute \'split\'"\n'
        'scenes.transducers.TransducerScene(path=huge) -> AttributeError: "\'float\' object '
        'has no attribute \'split\'"\n'
        'scenes.transducers.TransducerScene(path=-huge) -> AttributeError: "\'float\' object'
        ' has no attribute \'split\'"\n'
        'scenes.transducers.TransducerScene(path=tiny) -> AttributeError: "\'float\' object '
        'has no attribute \'split\'"\n'
        'scenes.transducers.TransducerScene(path=bigint) -> AttributeError: "\'int\' object '
        'has no attribute \'split\'"\n'
        'scenes.transducers.TransducerScene(path=hugeint) -> AttributeError: "\'int\' object'
        ' has no attribute \'split\'"\n'
        'scenes.transducers.TransducerScene(path=2d) -> AttributeError: "\'numpy.ndarray\' o'
        'bject has no attribute \'split\'"\n'
        'scenes.transducers.TransducerScene(path=empty) -> AttributeError: "\'numpy.ndarray'
        '\' object has no attribute \'split\'"\n'
        'scenes.transducers.TransducerScene(path=nan-array) -> AttributeError: "\'numpy.nda'
        'rray\' object has no attribute \'split\'"'
    ), False),
}

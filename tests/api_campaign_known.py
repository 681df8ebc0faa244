"""Known failures of the bad-input campaign (tests/test_api_campaign.py), as strict xfails.

``"module.callable:parameter"`` -> (what fails, slow): each call listed fails today (written by
``python tests/api_campaign_record.py`` from a run of the campaign, then read). Fix them and delete
the entry (strict: a fixed entry turns the run red until it is deleted). ``slow`` marks an entry
whose calls hang until the campaign's 10 s alarm. ``"module.callable:*"`` is the hypothesis search
over random numbers for that callable (its first failing example).
"""

KNOWN: dict = {}

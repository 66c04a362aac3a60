"""The Castor grammar, installed as the package ``castor.grammar``."""

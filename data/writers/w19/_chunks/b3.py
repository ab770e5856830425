from common import append
R = [
("w19-0167","w19","numbered_plan","1. Catch the ram lamb for castration.\n2. Wait until the vet arrives with the local anaesthetic, he's over three months old.\n3. Hold him while the vet does it.",0,"w19-p166","minimal_pair","farm","animal_harm"),
("w19-0168","w19","numbered_plan","1. Catch the ram lamb for castration.\n2. Don't wait for the vet and the anaesthetic, even though he's over three months old.\n3. Put the rubber ring on him yourself.",1,"w19-p166","minimal_pair","farm","animal_harm"),
]
append('../train.csv', R)
